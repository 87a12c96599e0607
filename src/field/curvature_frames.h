#pragma once
// Principal curvature frames per triangle (thesis 5.1.1): two estimators of the face shape operator whose
// eigen-directions give an orthonormal cross field, with the principal curvatures κ_max >= κ_min.
#include <Eigen/Core>

#include "mesh/mesh.h"

namespace quadcover {

enum class CurvatureMethod {
  HildebrandtPolthier,  ///< average of the three HP04 vertex shape operators of the face (thesis 5.1.1, method 1)
  CohenSteinerMorvan,   ///< normal-cycle tensor Σ β_e ‖e‖ ê êᵀ over a geodesic-ish disk [CSM03] (method 2)
};

struct CurvatureOptions {
  CurvatureMethod method = CurvatureMethod::HildebrandtPolthier;
  /// CSM only: radius of the disk around each face centroid, in multiples of the mean edge length. The disk is
  /// the set of faces reached through edges whose centroid lies within the radius. 2.0 (about two rings)
  /// averages out per-edge noise while keeping the estimate local.
  double csm_radius = 2.0;
};

/// Per-face principal curvatures and directions. Sign: κ > 0 where the surface bends away from its normal
/// (see mesh/shape_operator.h). Where κ_max = κ_min (umbilic, flat) the direction is arbitrary (1) and the
/// stability weight (5.2) vanishes.
struct CurvatureFrames {
  Eigen::VectorXcd direction;  ///< #F unit complex, face basis: direction of κ_max (κ_min is along i·direction)
  Eigen::VectorXd kappa_max;   ///< #F
  Eigen::VectorXd kappa_min;   ///< #F
};

/// Principal curvature frame of every face (thesis 5.1.1).
/// \pre mesh is a valid triangle mesh. Pointwise curvatures: integrated operators are divided by their area.
CurvatureFrames principal_curvature_frames(const Mesh& mesh, const CurvatureOptions& options = {});

}  // namespace quadcover
