#include "mesh/triangle_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace quadcover {

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;  // vertex region a
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;  // vertex region b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));  // edge ab
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;  // vertex region c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));  // edge ac
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));  // bc
  const double denom = va + vb + vc;
  if (denom == 0) return a;  // degenerate triangle
  return a + ab * (vb / denom) + ac * (vc / denom);
}

TriangleTree::TriangleTree(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  const int n = static_cast<int>(F.rows());
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  centroid_.resize(n);
  for (int f = 0; f < n; ++f) centroid_[f] = (V.row(F(f, 0)) + V.row(F(f, 1)) + V.row(F(f, 2))).transpose() / 3.0;
  if (n > 0) build(V, F, 0, n);
  // Corners in leaf order, contiguous: a leaf's triangles are read from one block instead of 3 strided rows each.
  tri_.resize(n);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) tri_[i][c] = V.row(F(order_[i], c)).transpose();
  centroid_ = {};
}

int TriangleTree::build(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, int begin, int end) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box, cbox;
  for (int i = begin; i < end; ++i) {
    for (int c = 0; c < 3; ++c) box.extend(V.row(F(order_[i], c)).transpose());
    cbox.extend(centroid_[order_[i]]);
  }
  nodes_[id].box = box;
  if (end - begin <= 4) {
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    return id;
  }
  int axis;
  cbox.sizes().maxCoeff(&axis);
  const int mid = (begin + end) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](int x, int y) { return centroid_[x][axis] < centroid_[y][axis]; });
  const int l = build(V, F, begin, mid);
  const int r = build(V, F, mid, end);
  nodes_[id].left = l;
  nodes_[id].right = r;
  return id;
}

double TriangleTree::squared_distance(const Eigen::Vector3d& p, int* face) const {
  int f = -1;
  Eigen::Vector3d q;
  const double d = nearest(p, f, q);
  if (face) *face = f;
  return d;
}

Eigen::Vector3d TriangleTree::closest_point(const Eigen::Vector3d& p, int* face) const {
  int f = -1;
  Eigen::Vector3d q = p;
  nearest(p, f, q);
  if (face) *face = f;
  return q;
}

double TriangleTree::nearest(const Eigen::Vector3d& p, int& best_face, Eigen::Vector3d& point) const {
  double best = std::numeric_limits<double>::infinity();
  best_face = -1;
  if (nodes_.empty()) return best;
  // Depth-first, nearer child first: at most one pending sibling per level, and median splits give a depth of at
  // most log2(#F) + 1 < 64 levels.
  struct Pending {
    int node;
    double bound;  // squared distance from p to the node's box
  };
  std::array<Pending, 64> stack;
  int top = 0;
  stack[top++] = {0, nodes_[0].box.squaredExteriorDistance(p)};
  while (top > 0) {
    const Pending pending = stack[--top];
    if (pending.bound >= best) continue;
    const Node& nd = nodes_[pending.node];
    if (nd.left < 0) {
      for (int i = nd.begin; i < nd.end; ++i) {
        const Triangle& t = tri_[i];
        const Eigen::Vector3d q = closest_point_on_triangle(p, t[0], t[1], t[2]);
        const double d = (q - p).squaredNorm();
        if (d < best) best = d, best_face = order_[i], point = q;
      }
      continue;
    }
    // visit the nearer child first
    const Pending l{nd.left, nodes_[nd.left].box.squaredExteriorDistance(p)},
        r{nd.right, nodes_[nd.right].box.squaredExteriorDistance(p)};
    if (l.bound < r.bound) {
      stack[top++] = r;
      stack[top++] = l;
    } else {
      stack[top++] = l;
      stack[top++] = r;
    }
  }
  return best;
}

}  // namespace quadcover
