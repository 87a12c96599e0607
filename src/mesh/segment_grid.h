#pragma once
// Closest points on a set of line segments through a uniform grid (feature-fidelity metric, projection onto feature
// polylines).
#include <Eigen/Core>
#include <vector>

namespace quadcover {

/// Closest-point queries on a fixed segment set. Each segment is binned into the grid cells its bounding box meets
/// (cell size about the mean segment length); a query scans shells of cells around the point until no unseen cell
/// can hold a closer segment. Build O(n), query ~O(1) near the segments. Results do not depend on the thread count.
class SegmentGrid {
 public:
  /// Segment s runs from V.row(E(s, 0)) to V.row(E(s, 1)). \pre the indices of E are rows of V.
  SegmentGrid(const Eigen::MatrixX3d& V, const Eigen::MatrixX2i& E);
  int num_segments() const { return static_cast<int>(a_.size()); }  ///< \pre none
  /// Squared distance from p to the nearest segment (infinity for an empty set); `segment` receives its index
  /// (the lowest among equally near ones; -1 for an empty set). \pre none
  double squared_distance(const Eigen::Vector3d& p, int* segment = nullptr) const;
  /// The point of the nearest segment closest to p (p itself for an empty set). \pre none
  Eigen::Vector3d closest_point(const Eigen::Vector3d& p, int* segment = nullptr) const;

 private:
  double nearest(const Eigen::Vector3d& p, int& segment, Eigen::Vector3d& point) const;
  Eigen::Array3i cell_of(const Eigen::Vector3d& p) const;  ///< unclamped cell coordinates
  std::vector<Eigen::Vector3d> a_, b_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double cell_ = 1;
  Eigen::Array3i dims_ = Eigen::Array3i::Ones();
  std::vector<int> offsets_;  ///< CSR: segments of cell c are items_[offsets_[c] .. offsets_[c + 1])
  std::vector<int> items_;
};

/// Closest point to p on the segment [a, b] (a for a degenerate segment). \pre none
Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace quadcover
