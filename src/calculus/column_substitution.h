#pragma once
// Triangular solves with a Cholesky factor stored by columns (SparseCholesky::solve_sparse): a forward substitution
// that visits only the columns a sparse right-hand side reaches, and a back substitution split on the elimination
// tree so that two disjoint subtrees are solved at once, each column with the same arithmetic as in one pass.
#include <complex>
#include <span>
#include <vector>

namespace quadcover {

/// A lower triangular factor L of P A Pᵀ = L Lᴴ by columns: column j holds rows i[p[j]] .. i[p[j+1]-1], the diagonal
/// first (real, positive). Non-owning.
template <class Scalar>
struct LowerColumns {
  int n = 0;
  const int* p = nullptr;
  const int* i = nullptr;
  const Scalar* x = nullptr;
};

/// The order of a back substitution on two cores: `top` first (descending), then `part[0]` and `part[1]` at once
/// (each descending). Every column of a part has its rows in its own part or in `top`. Empty parts: one pass.
struct BackSubstitutionSplit {
  std::vector<int> top, part[2];
  bool empty() const { return part[0].empty() || part[1].empty(); }  ///< \pre none
};

/// Splits the elimination tree of L (parent = smallest row below the diagonal) into whole subtrees of about equal
/// entries for two parts, their ancestors on top. Empty when L has fewer than `min_columns` columns, when the
/// ancestors would hold more than a tenth of the entries, or when a column's rows leave its part and the top (a
/// pattern without the elimination tree's closure). \pre L's columns start at their diagonal.
template <class Scalar>
BackSubstitutionSplit split_back_substitution(const LowerColumns<Scalar>& L, int min_columns);

/// y := L⁻¹ y from column `first` on, skipping columns whose entry is still zero (they change nothing below them):
/// a right-hand side of few entries costs their elimination-tree paths. \pre y has L.n entries; 0 <= first.
template <class Scalar>
void forward_substitute(const LowerColumns<Scalar>& L, int first, Scalar* y);

/// y := L⁻ᴴ y, by `split` on two cores when it is not empty (the same numbers as one pass).
/// \pre y has L.n entries; split was made for L or is empty.
template <class Scalar>
void back_substitute(const LowerColumns<Scalar>& L, const BackSubstitutionSplit& split, Scalar* y);

extern template BackSubstitutionSplit split_back_substitution(const LowerColumns<double>&, int);
extern template BackSubstitutionSplit split_back_substitution(const LowerColumns<std::complex<double>>&, int);
extern template void forward_substitute(const LowerColumns<double>&, int, double*);
extern template void forward_substitute(const LowerColumns<std::complex<double>>&, int, std::complex<double>*);
extern template void back_substitute(const LowerColumns<double>&, const BackSubstitutionSplit&, double*);
extern template void back_substitute(const LowerColumns<std::complex<double>>&, const BackSubstitutionSplit&,
                                     std::complex<double>*);

}  // namespace quadcover
