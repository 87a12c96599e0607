#pragma once
// Closest points on a triangle set through a bounding volume hierarchy (surface distances, projection onto the input).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace quadcover {

/// Closest-point queries on a fixed triangle set (AABB tree, median splits). Build O(n log n), query ~O(log n).
class TriangleTree {
 public:
  /// V #V by 3, F #F by 3. \pre every index of F is a row of V.
  TriangleTree(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);
  /// Squared distance from p to the nearest triangle (infinity for an empty set); `face` receives its index. \pre none
  double squared_distance(const Eigen::Vector3d& p, int* face = nullptr) const;
  /// The point of the nearest triangle closest to p (p itself for an empty set); `face` receives its index (-1).
  /// \pre none
  Eigen::Vector3d closest_point(const Eigen::Vector3d& p, int* face = nullptr) const;

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int left = -1, right = -1;  ///< children, or -1 for a leaf
    int begin = 0, end = 0;     ///< leaf range in order_
  };
  int build(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, int begin, int end);
  /// Squared distance to the nearest triangle, its index (-1 if none) and the closest point on it.
  double nearest(const Eigen::Vector3d& p, int& face, Eigen::Vector3d& point) const;
  using Triangle = std::array<Eigen::Vector3d, 3>;
  std::vector<int> order_;  // leaf order -> face
  std::vector<Node> nodes_;
  std::vector<Eigen::Vector3d> centroid_;  // during build() only
  std::vector<Triangle> tri_;              // corners of face order_[i]
};

/// Closest point to p on triangle (a, b, c) (region test on the barycentric coordinates). \pre none
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

}  // namespace quadcover
