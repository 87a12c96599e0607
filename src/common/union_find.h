#pragma once
// Disjoint sets with path halving and union by size: the one union-find of every stage (mesh connectivity, cut
// graphs, coverings, extraction).
#include <numeric>
#include <utility>
#include <vector>

namespace quadcover::detail {

class UnionFind {
 public:
  /// n singletons. \pre n >= 0
  explicit UnionFind(int n) { reset(n); }
  /// n singletons again (reuses the storage). \pre n >= 0
  void reset(int n) {
    parent_.resize(static_cast<std::size_t>(n));
    std::iota(parent_.begin(), parent_.end(), 0);
    size_.assign(static_cast<std::size_t>(n), 1);
  }
  /// The representative of x's set. \pre 0 <= x < n
  int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  /// Merges the sets of a and b; false if they were already one set. \pre 0 <= a, b < n
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
    return true;
  }

 private:
  std::vector<int> parent_, size_;
};

}  // namespace quadcover::detail
