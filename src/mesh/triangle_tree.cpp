#include "mesh/triangle_tree.h"

#include <algorithm>
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

TriangleTree::TriangleTree(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) : V_(V), F_(F) {
  const int n = static_cast<int>(F.rows());
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  centroid_.resize(n);
  for (int f = 0; f < n; ++f) centroid_[f] = (V.row(F(f, 0)) + V.row(F(f, 1)) + V.row(F(f, 2))).transpose() / 3.0;
  if (n > 0) build(0, n);
}

int TriangleTree::build(int begin, int end) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box, cbox;
  for (int i = begin; i < end; ++i) {
    for (int c = 0; c < 3; ++c) box.extend(V_.row(F_(order_[i], c)).transpose());
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
  const int l = build(begin, mid);
  const int r = build(mid, end);
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
  std::vector<int> stack = {0};
  while (!stack.empty()) {
    const Node& nd = nodes_[stack.back()];
    stack.pop_back();
    if (nd.box.squaredExteriorDistance(p) >= best) continue;
    if (nd.left < 0) {
      for (int i = nd.begin; i < nd.end; ++i) {
        const int f = order_[i];
        const Eigen::Vector3d q = closest_point_on_triangle(p, V_.row(F_(f, 0)), V_.row(F_(f, 1)), V_.row(F_(f, 2)));
        const double d = (q - p).squaredNorm();
        if (d < best) best = d, best_face = f, point = q;
      }
      continue;
    }
    // visit the nearer child first
    const double dl = nodes_[nd.left].box.squaredExteriorDistance(p),
                 dr = nodes_[nd.right].box.squaredExteriorDistance(p);
    if (dl < dr) {
      stack.push_back(nd.right);
      stack.push_back(nd.left);
    } else {
      stack.push_back(nd.left);
      stack.push_back(nd.right);
    }
  }
  return best;
}

}  // namespace quadcover
