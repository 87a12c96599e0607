// Column-wise triangular solves with a Cholesky factor. See column_substitution.h.
#include "calculus/column_substitution.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <queue>
#include <type_traits>
#include <utility>

namespace quadcover {
namespace {

template <class Scalar>
Scalar conjugate(Scalar v) {
  if constexpr (std::is_same_v<Scalar, double>)
    return v;
  else
    return std::conj(v);
}

/// The elimination tree of L: parent[j] = the smallest row below the diagonal of column j, -1 at a root.
template <class Scalar>
std::vector<int> elimination_tree(const LowerColumns<Scalar>& L) {
  std::vector<int> parent(static_cast<std::size_t>(L.size()), -1);
  for (int j = 0; j < L.size(); ++j)
    for (int q = 1; q < L.length[j]; ++q)
      if (parent[j] < 0 || L.rows[j][q] < parent[j]) parent[j] = L.rows[j][q];
  return parent;
}

/// Whether every column of each part has its rows in its own part or on top (part_of -1), and every top column its
/// rows on top: then the top, solved first, and each part read only what is already solved.
template <class Scalar>
bool parts_are_closed(const LowerColumns<Scalar>& L, const std::vector<int>& part_of) {
  for (int j = 0; j < L.size(); ++j)
    for (int q = 1; q < L.length[j]; ++q) {
      const int other = part_of[static_cast<std::size_t>(L.rows[j][q])];
      if (other != -1 && other != part_of[static_cast<std::size_t>(j)]) return false;
    }
  return true;
}

}  // namespace

template <class Scalar>
SubstitutionSplit split_substitution(const LowerColumns<Scalar>& L, int min_columns) {
  const int n = L.size();
  if (n < std::max(min_columns, 2)) return {};
  const std::vector<int> parent = elimination_tree(L);
  std::vector<long> entries(static_cast<std::size_t>(n)), below(static_cast<std::size_t>(n));
  std::vector<int> first_child(static_cast<std::size_t>(n), -1), next_sibling(static_cast<std::size_t>(n), -1);
  long total = 0;
  for (int j = 0; j < n; ++j) total += below[j] = entries[j] = L.length[j];
  for (int j = 0; j < n; ++j)
    if (parent[j] >= 0) below[parent[j]] += below[j];  // parent > j: its subtree is complete when it is reached
  for (int j = n - 1; j >= 0; --j)
    if (parent[j] >= 0) next_sibling[j] = first_child[parent[j]], first_child[parent[j]] = j;
  // Open the largest subtree (its root goes on top) while it holds more than half of what is left.
  std::priority_queue<std::pair<long, int>> trees;
  for (int j = 0; j < n; ++j)
    if (parent[j] < 0) trees.emplace(below[j], j);
  SubstitutionSplit split;
  long top_entries = 0;
  while (!trees.empty() && 2 * trees.top().first > total - top_entries) {
    const int root = trees.top().second;
    trees.pop();
    split.top.push_back(root);
    if (3 * (top_entries += entries[root]) > total) return {};
    for (int c = first_child[root]; c >= 0; c = next_sibling[c]) trees.emplace(below[c], c);
  }
  // Whole subtrees, largest first, to the part with fewer entries so far.
  std::vector<int> part_of(static_cast<std::size_t>(n), -1);
  long held[2] = {0, 0};
  std::vector<int> stack;
  for (; !trees.empty(); trees.pop()) {
    const int part = held[1] < held[0] ? 1 : 0;
    held[part] += trees.top().first;
    for (stack.assign(1, trees.top().second); !stack.empty();) {
      const int j = stack.back();
      stack.pop_back();
      part_of[static_cast<std::size_t>(j)] = part;
      split.part[part].push_back(j);
      for (int c = first_child[j]; c >= 0; c = next_sibling[c]) stack.push_back(c);
    }
  }
  if (!parts_are_closed(L, part_of)) return {};
  for (std::vector<int>* columns : {&split.top, &split.part[0], &split.part[1]})
    std::sort(columns->begin(), columns->end(), std::greater<>());
  split.top_position.assign(static_cast<std::size_t>(n), -1);
  for (std::size_t t = 0; t < split.top.size(); ++t) split.top_position[split.top[t]] = static_cast<int>(t);
  return split;
}

template <class Scalar>
void forward_substitute(const LowerColumns<Scalar>& L, int first, Scalar* y) {
  for (int j = first; j < L.size(); ++j) {
    if (y[j] == Scalar(0)) continue;
    const int* rows = L.rows[j];
    const Scalar* v = L.values[j];
    const Scalar yj = y[j] /= std::real(v[0]);
    for (int q = 1; q < L.length[j]; ++q) y[rows[q]] -= v[q] * yj;
  }
}

template <class Scalar>
void back_substitute(const LowerColumns<Scalar>& L, const SubstitutionSplit& split, Scalar* y) {
  const auto column = [&](int j) {
    const int* rows = L.rows[j];
    const Scalar* v = L.values[j];
    Scalar s = y[j];
    for (int q = 1; q < L.length[j]; ++q) s -= conjugate(v[q]) * y[rows[q]];
    y[j] = s / std::real(v[0]);
  };
  if (split.empty()) {
    for (int j = L.size() - 1; j >= 0; --j) column(j);
    return;
  }
  for (const int j : split.top) column(j);
  run_parts_side_by_side([&](int part) {
    for (const int j : split.part[part]) column(j);
  });
}

void run_parts_side_by_side(const std::function<void(int)>& part) {
  tbb::parallel_invoke([&] { part(0); }, [&] { part(1); });
}

template SubstitutionSplit split_substitution(const LowerColumns<double>&, int);
template SubstitutionSplit split_substitution(const LowerColumns<std::complex<double>>&, int);
template void forward_substitute(const LowerColumns<double>&, int, double*);
template void forward_substitute(const LowerColumns<std::complex<double>>&, int, std::complex<double>*);
template void back_substitute(const LowerColumns<double>&, const SubstitutionSplit&, double*);
template void back_substitute(const LowerColumns<std::complex<double>>&, const SubstitutionSplit&,
                              std::complex<double>*);

}  // namespace quadcover
