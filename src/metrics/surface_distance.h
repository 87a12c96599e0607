#pragma once
// Distance between a remeshed surface and its input: closest points on triangle sets through a bounding volume
// hierarchy; both directions sampled, reported relative to the input's bounding-box diagonal.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace quadcover {

/// Closest-point queries on a fixed triangle set (AABB tree, median splits). Build O(n log n), query ~O(log n).
class TriangleTree {
 public:
  /// V #V by 3, F #F by 3.
  TriangleTree(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);
  /// Squared distance from p to the nearest triangle (infinity for an empty set); `face` receives its index.
  double squared_distance(const Eigen::Vector3d& p, int* face = nullptr) const;

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int left = -1, right = -1;  ///< children, or -1 for a leaf
    int begin = 0, end = 0;     ///< leaf range in order_
  };
  int build(int begin, int end);
  Eigen::MatrixX3d V_;
  Eigen::MatrixX3i F_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
  std::vector<Eigen::Vector3d> centroid_;
};

/// Closest point to p on triangle (a, b, c) (region test on the barycentric coordinates).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

struct SurfaceDistance {
  double bbox_diagonal = 0;      ///< of the reference (input) mesh
  double mean_to_reference = 0;  ///< remesh samples → input, / diagonal
  double max_to_reference = 0;
  double mean_from_reference = 0;  ///< input vertices → remesh, / diagonal
  double max_from_reference = 0;
  double mean = 0, max = 0;      ///< symmetric: average of the two means, max of the two maxima (Hausdorff estimate)
};

/// Distances between a polygon mesh (fan-triangulated; sampled at vertices, edge midpoints and face centroids) and a
/// reference triangle mesh (sampled at its vertices).
SurfaceDistance surface_distance(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces,
                                 const Eigen::MatrixX3d& ref_V, const Eigen::MatrixX3i& ref_F);

}  // namespace quadcover
