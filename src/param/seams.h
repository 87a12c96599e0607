#pragma once
// Measuring a parameterization from its per-corner coordinates alone: the transition z ↦ i^k z + c across every
// interior edge (seamless iff c ∈ Z[i]), and the triangles that flip or collapse in parameter space.
#include <Eigen/Core>
#include <cmath>
#include <complex>
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
/// uv  #F by 3 per-corner coordinates. \pre uv is #F by 3.
SeamReport measure_seams(const Mesh& mesh, const Eigen::MatrixX3cd& uv, double relative_tolerance = 1e-9);

/// Orientation of the map's triangles, relative to the reference area A_ref(t) = A3D(t) · (Σ|A_uv| / Σ A3D) and
/// τ = flip_tolerance: *flipped* if A_uv(t) < −τ·A_ref(t), *collapsed* if |A_uv(t)| ≤ τ·A_ref(t). A valid
/// integer-grid map (thesis 2.1, requirement 2) has neither: non_positive = flipped + collapsed = 0.
struct FlipReport {
  int flipped = 0;                 ///< A_uv < −τ·A_ref
  int collapsed = 0;               ///< |A_uv| ≤ τ·A_ref
  int non_positive = 0;            ///< flipped + collapsed
  std::vector<int> flipped_faces;  ///< the non-positive ones (both kinds), ascending
  double parameter_area = 0;       ///< Σ signed areas (≈ number of unit squares covered)
};

inline constexpr double flip_tolerance = 1e-8;

/// flipped_triangles' test of one face: non-positive iff its parameter area is below zero or within `reference`
/// (τ·A_3D·Σ|A_uv|/ΣA_3D) of it; collapsed in the second case, flipped in the first. \pre reference >= 0
inline bool collapsed_uv_area(double area, double reference) { return std::abs(area) <= reference; }
inline bool non_positive_uv_area(double area, double reference) {  ///< \pre reference >= 0
  return collapsed_uv_area(area, reference) || area < 0;
}

/// The signed parameter area ½ Im(conj(uv1 − uv0)(uv2 − uv0)) of the triangle with corners uv0, uv1, uv2. \pre none
inline double signed_uv_area(Complex uv0, Complex uv1, Complex uv2) {
  return 0.5 * std::imag(std::conj(uv1 - uv0) * (uv2 - uv0));
}
/// The signed parameter area of face f. \pre f < #uv rows.
inline double signed_uv_area(const Eigen::MatrixX3cd& uv, Eigen::Index f) {
  return signed_uv_area(uv(f, 0), uv(f, 1), uv(f, 2));
}

/// Signed parameter areas ½ Im(conj(uv1 - uv0)(uv2 - uv0)) of all faces, judged against the 3D areas of `mesh`.
/// \pre uv is #F by 3.
FlipReport flipped_triangles(const Mesh& mesh, const Eigen::MatrixX3cd& uv, double tolerance = flip_tolerance);
/// The same with the 3D areas per face given (a soup that is not a Mesh: `render --uv-layout`). \pre #areas = #uv rows.
FlipReport flipped_triangles(const Eigen::VectorXd& face_areas, const Eigen::MatrixX3cd& uv,
                             double tolerance = flip_tolerance);

}  // namespace quadcover
