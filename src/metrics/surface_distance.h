#pragma once
// Distance between a remeshed surface and its input: closest points on triangle sets (mesh/triangle_tree.h); both
// directions sampled, reported relative to the input's bounding-box diagonal.
#include <Eigen/Core>
#include <vector>

namespace quadcover {

struct SurfaceDistance {
  double bbox_diagonal = 0;      ///< of the reference (input) mesh
  double mean_to_reference = 0;  ///< remesh samples → input, / diagonal
  double max_to_reference = 0;
  double mean_from_reference = 0;  ///< input vertices → remesh, / diagonal
  double max_from_reference = 0;
  double mean = 0, max = 0;  ///< symmetric: average of the two means, max of the two maxima (Hausdorff estimate)
};

/// Distances between a polygon mesh (fan-triangulated; sampled at vertices, edge midpoints and face centroids) and a
/// reference triangle mesh (sampled at its vertices).
/// \pre every face index is a row of V, every ref_F index a row of ref_V.
SurfaceDistance surface_distance(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces,
                                 const Eigen::MatrixX3d& ref_V, const Eigen::MatrixX3i& ref_F);

}  // namespace quadcover
