#pragma once
// Foldover-free final map (beyond the thesis; Garanzha, Kaporin, Kudryavtseva, Protais, Ray, Sokolov 2021,
// "Foldover-free maps in 50 lines of code"). With the seams, transitions, periods, branch points and the enforced
// curve constraints fixed, the map φ = base − corner_values(u) is affine in the real components (x_p, y_p) of the
// covering function u (param/harmonic_correction.h); per face its Jacobian relative to the frame it follows,
// J = (∇φ) Z⁻¹ (rows ∇φ⁰, ∇φ¹ in the face's frame), is real-linear in them. The untangler minimizes
//   F_ε(u) = Σ_t A_t f_ε(J_t),  f_ε(J) = [tr(JᵀJ) + λ (det² J + 1)] / χ(det J, ε),  χ(D, ε) = (D + √(ε² + D²)) / 2,
// finite for every map, so it starts from a folded one; ε decreases by the paper's rule (it stays large enough
// that the smallest determinant is inside the regularization while folds remain). Once every det J > 0, a polish
// minimizes F_0 (conformal plus area distortion, infinite on inverted and degenerate triangles) with the line
// search capped before the first inversion (Smith & Schaefer 2015): the map never leaves the injective set.
// Every step is a projected Newton step (the per-face Hessian made positive semi-definite) solved by the sparse
// Cholesky of the free components; the pattern is fixed and analysed once.
#include <Eigen/Core>
#include <vector>

#include "common/progress.h"
#include "param/disk_functions.h"
#include "param/harmonic_correction.h"
#include "param/parameterization.h"

namespace quadcover {

struct UntangleOptions {
  bool enabled = true;  ///< run when the final map has a non-positive triangle
  /// The folds are untangled in regions: the vertices within `rings` rings of them move, ×4 per failed attempt up
  /// to max_rings (≥ #F: the last attempt moves the whole map). Folds that a region of 32 rings cannot undo are
  /// held by the constraints (branch points rounded to one point a few edges apart): larger regions only cost time.
  /// The growth also ends after an attempt past the first that leaves as many folds as it was given: on the shipped
  /// meshes the next, 16× larger region then never removed one either (BENCHMARKS.md, "Untangling regions").
  int rings = 2, max_rings = 32;
  int max_iterations = 60;    ///< ε rounds per region at most (one projected Newton step each)
  int patience = 8;           ///< a region stops after this many rounds without fewer folds
  int polish_iterations = 8;  ///< Newton steps of the injective polish at most (0: none)
  double area_weight = 1.0;   ///< λ: weight of the area term (det² + 1) / det against the conformal term
  double tolerance = 1e-4;    ///< the polish stops when F_0 falls by less than this fraction in a step
  /// A face whose three corners the curve constraints put on one integer iso-line (a boundary ear, a triangle
  /// spanning a crease) has det ≡ 0 in the subspace. With this on, the `releasable` components of one of its
  /// corners are freed: the map becomes valid there and that curve leaves its iso-line near the vertex (the curve's
  /// reported deviation says by how much). Off: such faces stay collapsed and are reported as stuck.
  bool release_curve_corners = false;
  /// With release_curve_corners: when laying out rings again (below) leaves a wrong winding, the curve constraints
  /// within 2 rings of the wrongly wound vertices are given up once and the rings laid out again (a cone rounded
  /// onto the image of a curve passing a few edges away leaves the strip between them no width); kept only for
  /// fewer wrong windings at no more non-positive triangles (released_vertices lists them).
  bool release_near_wrong_windings = true;
  /// Before untangling, lay out again the rings around which the map winds other than the field's index says
  /// (param/ring_winding.h): no untangling in the subspace changes that winding at a branch point.
  bool rewind_rings = true;
};

/// f_ε(J) of one 2×2 Jacobian (∞ when ε = 0 and det J ≤ 0), with its gradient and Hessian in the entries
/// (J00, J01, J10, J11) when asked for. Exposed for tests. \pre eps >= 0.
double untangle_density(const Eigen::Matrix2d& J, double eps, double lambda, Eigen::Vector4d* gradient = nullptr,
                        Eigen::Matrix4d* hessian = nullptr);

/// The real components of u that the untangler may move: 2·#V flags (x_p at p, y_p at #V + p), 1 = fixed. Branch
/// points, vertices without faces and the `pinned` vertices (both components) are fixed, and so is every flagged
/// entry of `fixed_components` (2·#V or empty: the curve constraints of param/alignment.h). \pre layers of mesh.
std::vector<char> untangle_fixed_components(const Mesh& mesh, const VertexLayers& layers,
                                            const std::vector<int>& pinned, const std::vector<char>& fixed_components);

/// Untangles and polishes φ = base − correction.corner_values(u) from u0 with the components flagged in `fixed`
/// held at their u0 values (seams, periods and constraints stay exact). Z: the scaled gauged frame per face (the
/// Jacobian reference; faces where it is degenerate or mirrored use its RMS length times the identity). Fills
/// `result` (counts from param/seams.h, iterations, seconds) except its price. Returns u0 when the map has no
/// non-positive triangle and the new u otherwise (u0 as well if the untangling made the count worse). `releasable`
/// (2·#V or empty): fixed components that options.release_curve_corners may free (the curve constraints).
/// \pre fixed has 2·#V entries, u0 has #V. \throw NumericalError if a factorization fails.
Eigen::VectorXcd untangle_map(const Mesh& mesh, const HarmonicCorrection& correction, const Eigen::MatrixX3cd& base,
                              const FramePairs& Z, const std::vector<char>& fixed, const Eigen::VectorXcd& u0,
                              const UntangleOptions& options, ProgressSink& progress,
                              ParamDiagnostics::Untangling& result, const std::vector<char>& releasable = {});
/// The same for φ = base − layered_values(mesh, layers, u): any layering of a covering function that the map's
/// transitions preserve (i^λ_t = i^k_e i^λ_s across every edge at vertices off the branch points), e.g. the
/// subspace of a map lifted to a refined mesh (pipeline/split_map.h). \throw NumericalError as the untangle_map above.
Eigen::VectorXcd untangle_map(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                              const FramePairs& Z, const std::vector<char>& fixed, const Eigen::VectorXcd& u0,
                              const UntangleOptions& options, ProgressSink& progress,
                              ParamDiagnostics::Untangling& result, const std::vector<char>& releasable = {});

/// The injective polish alone (F_0 with the line search capped before the first inversion, at most
/// options.polish_iterations Newton steps) of the components of the `region` vertices that `fixed` leaves free, on a
/// map with no non-positive triangle: it never passes a degenerate triangle, so no winding changes. Adds its steps to
/// result.polish_iterations; returns u0 if the map has a non-positive triangle or the region is empty.
/// \pre as untangle_map; region vertices in [0, #V). \throw NumericalError if a factorization fails.
Eigen::VectorXcd polish_map(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                            const FramePairs& Z, const std::vector<char>& fixed, const Eigen::VectorXcd& u0,
                            const std::vector<int>& region, const UntangleOptions& options, ProgressSink& progress,
                            ParamDiagnostics::Untangling& result);

/// What options.release_curve_corners does before an untangling, alone: for every face the components in `fixed`
/// hold at det ≡ 0 with φ = base, frees the `releasable` components of its first corner whose release unsticks it.
/// Returns the released vertices (ascending); `fixed` is updated. \pre sizes as for untangle_map.
std::vector<int> release_stuck_corners(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                                       const FramePairs& Z, std::vector<char>& fixed,
                                       const std::vector<char>& releasable);

}  // namespace quadcover
