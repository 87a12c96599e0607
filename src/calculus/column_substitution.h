#pragma once
// Triangular solves with a Cholesky factor stored by columns (SparseCholesky::solve_sparse, the exact E_D evaluation
// of optimize/updatable_cholesky.h): a forward substitution that visits only the columns a sparse right-hand side
// reaches, and substitutions split on the elimination tree so that two disjoint subtrees are solved at once.
#include <complex>
#include <functional>
#include <span>
#include <type_traits>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

/// A lower triangular factor L of P A Pᵀ = L Lᴴ by columns, read in place: column j holds length[j] entries, rows
/// rows[j][0 ..] and values values[j][0 ..], the diagonal first (real, positive). A supernodal factor's column is a
/// slice of its supernode's rows and block; a compressed one's a slice of its arrays (compressed()).
template <class Scalar>
struct LowerColumns {
  std::vector<const int*> rows;
  std::vector<const Scalar*> values;
  std::vector<int> length;
  int size() const { return static_cast<int>(length.size()); }  ///< \pre none
  /// Column j at p[j] .. p[j+1]-1 of i and x. \pre p has n + 1 entries.
  static LowerColumns compressed(int n, const int* p, const int* i, const Scalar* x) {
    LowerColumns L;
    L.rows.resize(static_cast<std::size_t>(n));
    L.values.resize(static_cast<std::size_t>(n));
    L.length.resize(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) L.rows[j] = i + p[j], L.values[j] = x + p[j], L.length[j] = p[j + 1] - p[j];
    return L;
  }
};

/// Factors of fewer columns are substituted in one pass (two cores do not pay below).
constexpr int kSplitSubstitutionMinColumns = 20000;

/// Two disjoint sets of whole subtrees of the elimination tree (`part`) and their ancestors (`top`), each list in
/// descending order; top_position[j] is j's place in `top`, -1 off it. Every column of a part has its rows in its
/// own part or in `top`. A back substitution solves the top, then the parts at once; a forward one the parts at once,
/// then the top. Empty parts: one pass.
struct SubstitutionSplit {
  std::vector<int> top, part[2], top_position;
  bool empty() const { return part[0].empty() || part[1].empty(); }  ///< \pre none
};

/// Splits the elimination tree of L (parent = smallest row below the diagonal) into whole subtrees of about equal
/// entries for two parts, their ancestors on top. Empty when L has fewer than `min_columns` columns, when the
/// ancestors would hold more than a third of the entries (they are solved on one core), or when a column's rows
/// leave its part and the top (a pattern without the elimination tree's closure). \pre L's columns start at their
/// diagonal.
template <class Scalar>
SubstitutionSplit split_substitution(const LowerColumns<Scalar>& L, int min_columns);

/// part(0) and part(1) on two cores (tbb::parallel_invoke); returns when both have. \pre none
void run_parts_side_by_side(const std::function<void(int)>& part);

/// y := L⁻¹ y from column `first` on, skipping columns whose entry is still zero (they change nothing below them):
/// a right-hand side of few entries costs their elimination-tree paths. \pre y has L.size() entries; 0 <= first.
template <class Scalar>
void forward_substitute(const LowerColumns<Scalar>& L, int first, Scalar* y);

/// y := L⁻¹ y by `split` on two cores (not empty): each part's columns ascending, their updates of top rows summed
/// apart and added part by part, then the top ascending. The same numbers whatever the threads, not bitwise one
/// pass's (the top rows sum in another order). `values(j)` points to column j's values (L.values is not read: a
/// factor may have columns swapped in). \pre y has L.size() entries; split was made for L's pattern.
template <class Scalar, class ColumnValues>
void forward_substitute_split(const LowerColumns<Scalar>& L, const SubstitutionSplit& split, ColumnValues values,
                              Scalar* y);

/// y := L⁻ᴴ y, by `split` on two cores when it is not empty (the same numbers as one pass).
/// \pre y has L.size() entries; split was made for L or is empty.
template <class Scalar>
void back_substitute(const LowerColumns<Scalar>& L, const SubstitutionSplit& split, Scalar* y);

/// a·b (complex: mesh.h's product, without std::complex's NaN branches). \pre none
template <class Scalar>
Scalar column_product(Scalar a, Scalar b) {
  if constexpr (std::is_same_v<Scalar, double>)
    return a * b;
  else
    return product(a, b);
}

template <class Scalar, class ColumnValues>
void forward_substitute_split(const LowerColumns<Scalar>& L, const SubstitutionSplit& split, ColumnValues values,
                              Scalar* y) {
  std::vector<Scalar> held[2];
  const auto column = [&](int j, Scalar* top_sums) {
    const Scalar* v = values(j);
    const Scalar yj = y[j] /= std::real(v[0]);
    const int* rows = L.rows[j];
    for (int q = 1; q < L.length[j]; ++q) {
      const int row = rows[q], t = top_sums ? split.top_position[static_cast<std::size_t>(row)] : -1;
      (t >= 0 ? top_sums[t] : y[row]) -= column_product(v[q], yj);
    }
  };
  run_parts_side_by_side([&](int part) {
    held[part].assign(split.top.size(), Scalar(0));
    for (auto j = split.part[part].rbegin(); j != split.part[part].rend(); ++j) column(*j, held[part].data());
  });
  for (std::size_t t = 0; t < split.top.size(); ++t) y[split.top[t]] += held[0][t] + held[1][t];
  for (auto j = split.top.rbegin(); j != split.top.rend(); ++j) column(*j, nullptr);
}

extern template SubstitutionSplit split_substitution(const LowerColumns<double>&, int);
extern template SubstitutionSplit split_substitution(const LowerColumns<std::complex<double>>&, int);
extern template void forward_substitute(const LowerColumns<double>&, int, double*);
extern template void forward_substitute(const LowerColumns<std::complex<double>>&, int, std::complex<double>*);
extern template void back_substitute(const LowerColumns<double>&, const SubstitutionSplit&, double*);
extern template void back_substitute(const LowerColumns<std::complex<double>>&, const SubstitutionSplit&,
                                     std::complex<double>*);

}  // namespace quadcover
