#include "mesh/segment_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace quadcover {

Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double len2 = d.squaredNorm();
  if (!(len2 > 0)) return a;
  return a + std::clamp((p - a).dot(d) / len2, 0.0, 1.0) * d;
}

SegmentGrid::SegmentGrid(const Eigen::MatrixX3d& V, const Eigen::MatrixX2i& E) {
  const int n = static_cast<int>(E.rows());
  if (n == 0) return;
  a_.resize(static_cast<std::size_t>(n));
  b_.resize(static_cast<std::size_t>(n));
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  double total = 0;
  for (int s = 0; s < n; ++s) {
    a_[s] = V.row(E(s, 0)).transpose();
    b_[s] = V.row(E(s, 1)).transpose();
    lo = lo.cwiseMin(a_[s]).cwiseMin(b_[s]);
    hi = hi.cwiseMax(a_[s]).cwiseMax(b_[s]);
    total += (b_[s] - a_[s]).norm();
  }
  // Cells about one segment long, but no more than ~2 cells per segment over the box (flat or sparse sets).
  const Eigen::Vector3d extent = (hi - lo).cwiseMax(1e-12 * std::max(1.0, (hi - lo).maxCoeff()));
  const double volume_cell = std::cbrt(extent.prod() / (2.0 * n));
  cell_ = std::max({total / n, volume_cell, 1e-12 * extent.maxCoeff()});
  origin_ = lo;
  for (int k = 0; k < 3; ++k) dims_[k] = std::max(1, static_cast<int>(std::floor(extent[k] / cell_)) + 1);
  const auto index = [&](const Eigen::Array3i& c) { return (c[2] * dims_[1] + c[1]) * dims_[0] + c[0]; };
  const auto cells_of = [&](int s, auto&& visit) {
    const Eigen::Array3i c0 = cell_of(a_[s].cwiseMin(b_[s])).max(0).min(dims_ - 1);
    const Eigen::Array3i c1 = cell_of(a_[s].cwiseMax(b_[s])).max(0).min(dims_ - 1);
    for (int z = c0[2]; z <= c1[2]; ++z)
      for (int y = c0[1]; y <= c1[1]; ++y)
        for (int x = c0[0]; x <= c1[0]; ++x) visit(index({x, y, z}));
  };
  offsets_.assign(static_cast<std::size_t>(dims_.prod()) + 1, 0);
  for (int s = 0; s < n; ++s) cells_of(s, [&](int c) { ++offsets_[static_cast<std::size_t>(c) + 1]; });
  for (std::size_t c = 1; c < offsets_.size(); ++c) offsets_[c] += offsets_[c - 1];
  items_.resize(static_cast<std::size_t>(offsets_.back()));
  std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
  for (int s = 0; s < n; ++s) cells_of(s, [&](int c) { items_[static_cast<std::size_t>(fill[c]++)] = s; });
}

Eigen::Array3i SegmentGrid::cell_of(const Eigen::Vector3d& p) const {
  const Eigen::Array3d c = ((p - origin_) / cell_).array().floor();
  // Clamp far outside points to a range that keeps the shell arithmetic in int.
  return c.max(-1e6).min(1e6).cast<int>();
}

double SegmentGrid::nearest(const Eigen::Vector3d& p, int& segment, Eigen::Vector3d& point) const {
  segment = -1;
  point = p;
  double best = std::numeric_limits<double>::infinity();
  if (a_.empty()) return best;
  const Eigen::Array3i c = cell_of(p);
  const auto visit = [&](int x, int y, int z) {
    const int cell = (z * dims_[1] + y) * dims_[0] + x;
    for (int i = offsets_[cell]; i < offsets_[cell + 1]; ++i) {
      const int s = items_[static_cast<std::size_t>(i)];
      const Eigen::Vector3d q = closest_point_on_segment(p, a_[s], b_[s]);
      const double d2 = (q - p).squaredNorm();
      if (d2 < best || (d2 == best && s < segment)) best = d2, segment = s, point = q;
    }
  };
  // Shell k: the cells at Chebyshev distance k from c. Cells beyond shell k are at least k·cell_ away from p.
  const Eigen::Array3i below = (-c).max(0), above = (c - dims_ + 1).max(0);
  const int k0 = std::max(below.maxCoeff(), above.maxCoeff());
  const int k_last = std::max((c - 0).abs().max((c - dims_ + 1).abs()).maxCoeff(), k0);
  for (int k = k0; k <= k_last; ++k) {
    const Eigen::Array3i lo = (c - k).max(0), hi = (c + k).min(dims_ - 1);
    for (int x = lo[0]; x <= hi[0]; ++x)
      for (int y = lo[1]; y <= hi[1]; ++y) {
        if (std::abs(x - c[0]) == k || std::abs(y - c[1]) == k) {
          for (int z = lo[2]; z <= hi[2]; ++z) visit(x, y, z);
        } else {
          if (c[2] - k >= 0) visit(x, y, c[2] - k);
          if (k > 0 && c[2] + k < dims_[2]) visit(x, y, c[2] + k);
        }
      }
    const double reach = k * cell_;
    if (best <= reach * reach) break;
  }
  return best;
}

double SegmentGrid::squared_distance(const Eigen::Vector3d& p, int* segment) const {
  int s;
  Eigen::Vector3d q;
  const double d2 = nearest(p, s, q);
  if (segment) *segment = s;
  return d2;
}

Eigen::Vector3d SegmentGrid::closest_point(const Eigen::Vector3d& p, int* segment) const {
  int s;
  Eigen::Vector3d q;
  nearest(p, s, q);
  if (segment) *segment = s;
  return q;
}

}  // namespace quadcover
