#pragma once
// The result of the QuadCover parameterization (thesis Chapters 2 and 4): a seamless integer-grid map.
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "common/stage_meter.h"
#include "field/frame_field.h"
#include "mesh/mesh.h"

namespace quadcover {

/// What the stages of parameterize() did and measured, beside the map itself (Parameterization).
struct ParamDiagnostics {
  /// Rounding of the periods (6.3): the strategy that ran, the number of real variables, E_H = xᵀPx predicted by the
  /// period matrix for direct rounding and for the chosen periods (before the even-branch fix-up and the curve
  /// alignment; after the cone separation's steps, which include the fix-up), the candidates the search evaluated
  /// and whether the exact solver proved optimality.
  struct Rounding {
    std::string strategy = "direct";
    int variables = 0;
    double energy_direct = 0, energy_rounded = 0;
    long long candidates = 0;
    bool proven_optimal = false;
    bool stopped_early = false;  ///< cancelled: the direct rounding or the search's best periods so far were kept
    double period_matrix_asymmetry = 0;  ///< max |P_ij − P_ji| / max P_ii (round-off)
    /// With the curves rounded with the periods (param/curve_rounding.h): the lines' closing and branch-point
    /// conditions the rounding weighed, and how many hold with the rounded periods.
    int curve_conditions = 0, curve_conditions_met = 0;
    int curve_lines = 0;  ///< lines whose integers were rounded with the periods (0: the period matrix alone)
    /// The map with the curves rounded with the periods was less valid: this one rounds with the period matrix alone.
    bool curve_rounding_dropped = false;
    /// Branch point pairs within kWatchedRings that the rounding put on one point, how many stay there, and those
    /// re-rounded periods set apart (ParamOptions::separate_close_cones, param/cone_separation.h).
    std::vector<std::pair<int, int>> coincident_cones, separated_cones;
    int coincident_cone_pairs_left = 0;
  } rounding;
  /// Closed components without branch points whose field has rotational holonomy (the gauged matching ≢ 0 around a
  /// handle). No seamless immersion exists there (a cone-free flat metric on a closed surface has trivial rotational
  /// holonomy): the map degenerates and the caller should warn; the cure is a field with branch points.
  std::vector<int> holonomy_without_branch_points;
  /// Even branch points the fix-up could not move to an integer point (rotated lattice), normally empty.
  std::vector<int> unfixed_even_branch_points;
  /// Largest deviation of a cut translation from the lattice before snapping, and of the disk integration
  /// (|two endpoint estimates of a translation| on the curl-free field): diagnostics, round-off sized.
  double max_translation_residual = 0, integration_mismatch = 0;
  /// Lines left free because they close on themselves inconsistently (Parameterization::aligned_curves).
  int alignment_conflicts = 0;
  /// ARAP relaxation of the final solve (param/relaxation.h): local/global rounds run, the mean ARAP distortion at
  /// the grid scale before and after, and its price E_R = ½‖X̃ − ∇φ̃‖² − E_D − E_H of the relaxed map.
  struct Relaxation {
    int iterations = 0;
    bool stopped_early = false;  ///< ended by a stop (ProgressSink::skip_improvements) before it converged
    double rigidity_before = 0, rigidity_after = 0;
    double energy = 0;
  } relaxation;
  /// Local stiffening of the final solve (param/stiffening.h): re-solves run, the one kept (0: none), flipped
  /// triangles before and after, and its further price E_K, so that E_D + E_H + E_R + E_K = ½‖X̃ − ∇φ̃‖²
  /// (E_K = 0 if none kept; after a relaxation E_K can be negative: the stiffened map may be nearer the field).
  struct Stiffening {
    int iterations = 0, kept_iteration = 0, flipped_before = 0, flipped_after = 0;
    double energy = 0;
  } stiffening;
  /// Untangling of the final map (param/untangle.h), run when it has a non-positive triangle (param/seams.h): ε
  /// rounds and polish steps run, non-positive triangles before and after, the smallest det of the Jacobian relative
  /// to the frame after, seconds, and its price E_U = ½‖X̃ − ∇φ̃‖² − E_D − E_H − E_R − E_K (0 if it did not run).
  struct Untangling {
    int iterations = 0, polish_iterations = 0, non_positive_before = 0, non_positive_after = 0;
    int regions = 0;  ///< regions untangled (UntangleOptions::rings: each a system of its own)
    double min_det = 0, seconds = 0, energy = 0;
    /// Faces the subspace holds at det ≤ 0 (all corners fixed, or two pinned to one point such as adjacent branch
    /// points rounded to one integer point): no map in it unfolds them; they stay non-positive.
    std::vector<int> stuck_faces;
    /// Other faces left non-positive: no injective map was found in the subspace around them (e.g. a triangle
    /// whose corners are held in the wrong order by branch points and curve constraints).
    std::vector<int> unresolved_faces;
    /// Vertices whose curve constraint was given up to unstick a face (UntangleOptions::release_curve_corners).
    std::vector<int> released_vertices;
    /// Vertices whose ring was laid out again before the untangling because the map wound around them other than
    /// the field's index says (param/ring_winding.h).
    std::vector<int> rewound_vertices;
    /// Those of them, branch points, whose disk was laid out again in the cone's chart (param/cone_disk_layout.h).
    std::vector<int> cone_disk_vertices;
  } untangling;
  /// Wall-clock seconds and peak resident bytes per stage, in pipeline order (common/stage_meter.h).
  StageSeconds stage_seconds;
  StagePeakBytes stage_peak_bytes;
};

struct Parameterization {
  /// #F by 3: φ = φ⁰ + iφ¹ at each corner (CornerData), in grid units: integer iso-lines are the quad edges.
  Eigen::MatrixX3cd uv;
  /// Per edge e (s = EF(e,0), t = EF(e,1)): across e the coordinates satisfy φ_t = i^{rotation_e} φ_s + translation_e,
  /// with translation_e ∈ Z[i] (the seamless transition). Both 0 where φ is continuous and on boundary edges.
  Eigen::VectorXi transition_rotation;      ///< #E, in 0..3
  Eigen::VectorXcd transition_translation;  ///< #E
  /// Edges of the cut along which φ may jump (#E, 1 = cut).
  Eigen::VectorXi cut_edges;
  /// Branch points of the guiding field (vertices with non-integer index).
  std::vector<BranchPoint> branch_points;
  /// Energies (thesis 6.1.1), measured on the covering M̃ in grid units: E_D = ½‖X̃_C‖² (curl part removed),
  /// E_H = ½‖H̃_d‖² (harmonic correction); E_D + E_H = ½‖X̃ - ∇φ̃‖². On M this is Σ_t A_t |·|² of both frame
  /// vectors (layers 2 and 3 repeat layers 0 and 1 with opposite sign).
  double energy_curl = 0, energy_harmonic = 0;

  /// #F: the quarter-turn gauge r_f of each face: on face f, ∇φ approximates scale · i^{r_f} Z_f (frame-complex i:
  /// i(X, Y) = (-Y, X)), i.e. ∇φ⁰ ≈ the first and ∇φ¹ ≈ the second vector of the turned frame.
  Eigen::VectorXi face_rotation;
  /// Grid units per unit of |Z| per model length: the field is scaled by `scale` before integration.
  double scale = 1;
  /// Target quad edge length h in model units (scale = 1 / (h · RMS frame length)).
  double edge_length = 0;
  /// Per connected component, how many times finer than h its grid is (param/density.h; empty: 1 everywhere).
  std::vector<double> component_density;
  /// h_sym (4.1): the number of real symmetric periods that were rounded, and the complex periods b_j of the paths
  /// before (after the constant gauge) and after rounding (one per path of the cut graph; the dependent path of each
  /// component is made integral by the constant of φ at no cost).
  int h_sym = 0;
  std::vector<Complex> periods, rounded_periods;
  /// Boundary / feature curves put on integer iso-lines (ParamOptions::alignment), each with its largest
  /// deviation (ParamDiagnostics::alignment_conflicts counts the lines left free).
  struct Curve {
    std::vector<int> edges;
    /// Per edge, the coordinate (0: φ⁰, 1: φ¹) constant along it in its face EF(e,0) (or the boundary edge's face),
    /// and the integer it should equal there (the line seen through the cut's transitions).
    std::vector<int> edge_coordinates;
    std::vector<double> edge_values;
    int coordinate = 0;  ///< of the first edge
    double value = 0, max_deviation = 0;
    /// False for lines left free (deviation reported): those that cannot be integer iso-lines with the rounded
    /// periods, and those param/alignment.h CurveLimits leaves free.
    bool enforced = true;
    /// Why a line is left free (empty when enforced): "two branch points at different integers", "closes on
    /// itself with another integer", "meets another line at another integer", "shorter than the minimum length",
    /// "too far from an integer", "wiggles more than the maximum spread".
    std::string left_free_because;
  };
  std::vector<Curve> aligned_curves;
  /// The seamless affine subspace of the final map, the one the untangler moves in (param/untangle.h): for every
  /// covering function δu that is 0 on the fixed components, uv − i^{layer} δu (0 at branch points) keeps every
  /// transition, period, branch point and enforced curve of the map.
  struct Subspace {
    Eigen::MatrixX3i layer;   ///< #F by 3: λ per corner
    Eigen::VectorXi branch;   ///< #V: 1 at branch points (both components held)
    std::vector<char> fixed;  ///< 2·#V flags (x_p at p, y_p at #V + p), 1 = held
  } subspace;
  /// The stages' reports: rounding, relaxation, stiffening, untangling, timings and round-off checks.
  ParamDiagnostics diagnostics;
};

}  // namespace quadcover
