#include "metrics/surface_distance.h"

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
  double best = std::numeric_limits<double>::infinity();
  int best_face = -1;
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
        if (d < best) best = d, best_face = f;
      }
      continue;
    }
    // visit the nearer child first
    const double dl = nodes_[nd.left].box.squaredExteriorDistance(p), dr = nodes_[nd.right].box.squaredExteriorDistance(p);
    if (dl < dr) {
      stack.push_back(nd.right);
      stack.push_back(nd.left);
    } else {
      stack.push_back(nd.left);
      stack.push_back(nd.right);
    }
  }
  if (face) *face = best_face;
  return best;
}

SurfaceDistance surface_distance(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces,
                                 const Eigen::MatrixX3d& ref_V, const Eigen::MatrixX3i& ref_F) {
  SurfaceDistance d;
  Eigen::AlignedBox3d box;
  for (int i = 0; i < ref_V.rows(); ++i) box.extend(ref_V.row(i).transpose());
  d.bbox_diagonal = ref_V.rows() ? box.diagonal().norm() : 0;
  if (d.bbox_diagonal <= 0 || faces.empty()) return d;
  // Fan triangulation of the polygons.
  std::vector<Eigen::Vector3i> tris;
  for (const auto& f : faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) tris.push_back({f[0], f[i], f[i + 1]});
  Eigen::MatrixX3i T(tris.size(), 3);
  for (std::size_t i = 0; i < tris.size(); ++i) T.row(i) = tris[i].transpose();
  const TriangleTree to_ref(ref_V, ref_F), to_remesh(V, T);
  // Samples of the remesh.
  std::vector<Eigen::Vector3d> samples;
  std::vector<char> used(V.rows(), 0);
  for (const auto& f : faces) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < f.size(); ++i) {
      used[f[i]] = 1;
      c += V.row(f[i]).transpose();
      if (f[i] < f[(i + 1) % f.size()]) samples.push_back(0.5 * (V.row(f[i]) + V.row(f[(i + 1) % f.size()])).transpose());
    }
    samples.push_back(c / static_cast<double>(f.size()));
  }
  for (int v = 0; v < V.rows(); ++v)
    if (used[v]) samples.push_back(V.row(v).transpose());
  double sum = 0;
  for (const auto& p : samples) {
    const double dist = std::sqrt(to_ref.squared_distance(p));
    sum += dist;
    d.max_to_reference = std::max(d.max_to_reference, dist);
  }
  d.mean_to_reference = sum / static_cast<double>(samples.size()) / d.bbox_diagonal;
  d.max_to_reference /= d.bbox_diagonal;
  sum = 0;
  for (int v = 0; v < ref_V.rows(); ++v) {
    const double dist = std::sqrt(to_remesh.squared_distance(ref_V.row(v).transpose()));
    sum += dist;
    d.max_from_reference = std::max(d.max_from_reference, dist);
  }
  d.mean_from_reference = sum / static_cast<double>(ref_V.rows()) / d.bbox_diagonal;
  d.max_from_reference /= d.bbox_diagonal;
  d.mean = 0.5 * (d.mean_to_reference + d.mean_from_reference);
  d.max = std::max(d.max_to_reference, d.max_from_reference);
  return d;
}

}  // namespace quadcover
