#pragma once
// Measuring a parameterization from its per-corner coordinates alone: the transition z ↦ i^k z + c across every
// interior edge (seamless iff c ∈ Z[i]), and the triangles that flip orientation in parameter space.
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

struct SeamReport {
  bool seamless = false;         ///< every interior edge has a transition with c ∈ Z[i] within the tolerance
  double max_transition_error = 0;  ///< largest |c - [c]| or endpoint disagreement, in grid units
  double parameter_extent = 0;   ///< diagonal of the bounding box of all coordinates
  int cut_edges = 0;             ///< interior edges whose transition is not the identity
  std::vector<int> bad_edges;    ///< edges whose error exceeds the tolerance
};

/// For each interior edge (s = EF(e,0), t = EF(e,1)) finds k ∈ 0..3 and c ∈ Z[i] best satisfying
/// uv_t = i^k uv_s + c at both endpoints. Tolerance: relative_tolerance × parameter extent.
/// uv  #F by 3 per-corner coordinates.
SeamReport measure_seams(const Mesh& mesh, const Eigen::MatrixX3cd& uv, double relative_tolerance = 1e-9);

struct FlipReport {
  int flipped = 0;                 ///< triangles with negative signed area in parameter space
  int degenerate = 0;              ///< triangles with |area| below 1e-12 × mean |area|
  std::vector<int> flipped_faces;  ///< their indices
  double parameter_area = 0;       ///< Σ signed areas (≈ number of unit squares covered)
};

/// Signed parameter areas ½ Im(conj(uv1 - uv0)(uv2 - uv0)) of all faces.
FlipReport flipped_triangles(const Eigen::MatrixX3cd& uv);

}  // namespace quadcover
