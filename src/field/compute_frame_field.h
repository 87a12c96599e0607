#pragma once
// The whole frame-field stage (thesis Chapter 5): curvature frames, feature alignment, trusted regions,
// propagation, smoothing, indices.
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "common/progress.h"
#include "field/curvature_frames.h"
#include "field/feature_alignment.h"
#include "field/frame_field.h"
#include "field/singularity_split.h"
#include "mesh/mesh.h"

namespace quadcover {

/// How the frames of the untrusted faces are obtained before smoothing.
enum class Fill {
  /// Thesis 5.1.2: breadth-first parallel transport from the trusted faces. Seams where propagated regions meet
  /// leave spurious branch points that the fixed-matching smoothing (5.3) cannot remove.
  Propagate,
  /// Global smooth solve of the power field u = X^4 (field/power_field.h) aligned to the trusted curvature
  /// directions with weight ω_t^stable (5.2) and exactly to the constrained faces; its matching is then the
  /// straightest one (5.1) and the thesis smoothing (5.3) runs on top.
  Smooth,
};

struct FieldOptions {
  CurvatureOptions curvature;  ///< estimator of the principal curvature frames (default HP)
  FeatureOptions features;     ///< boundary / sharp-edge alignment (default on, 35°)
  /// Fraction of faces whose curvature frames are trusted (5.1.2); the thesis recommends 10-30%.
  double trusted_fraction = 0.2;
  /// Default Smooth: on bunny_3k / cow / bunny_20k_holes it leaves 42 / 182 / 66 branch points where
  /// propagation leaves 77 / 259 / 251 (BENCHMARKS.md, "Frame field").
  Fill fill = Fill::Smooth;
  /// Fill::Smooth: alignment strength μ of PowerFieldProblem. Larger values follow the curvature frames more
  /// closely at the price of curl (E_D) and eventually branch points: without the smoothing step, the mean
  /// deviation from the principal directions on the 5% most stable faces of bunny_3k / bunny_20k_holes is
  /// 13° / 19° at μ = 100, 10° / 15° at 1000, 8° / 12° at 3000. The smoothing (5.3) then pulls the trusted
  /// frames back towards the curvature directions (its E_A targets them), to 8° / 7° at the default.
  double fill_alignment = 1000.0;
  /// Fill::Smooth: Ginzburg–Landau weight σ and majorize-minimize steps of PowerFieldProblem. σ = 1000 (core
  /// radius ≈ 3% of √area) with 10 steps removes a few more close ± pairs and lowers E_D of the parameterization
  /// by 10-40% on the test meshes, for about one extra factorization and 10 triangular solve pairs.
  double fill_unit_weight = 1000.0;
  int fill_iterations = 10;
  /// λ of (5.3) in (0, 1]: 1 ignores the curvature directions (only fixed faces anchor the field), small values
  /// keep trusted frames at their curvature directions (with Fill::Smooth, E_A measures the rotation from the
  /// filled frame to the nearest curvature direction: FrameSmoother::set_alignment_targets). 0.5 weighs the
  /// (scale-normalized) terms equally; with Fill::Propagate it lowers E_S of the propagated field 3-10×
  /// (bunny_3k 660 -> 213, fandisk 360 -> 48), within a few % of λ = 0.9, while E_A stays about half as large
  /// as with λ = 0.9.
  double lambda = 0.5;
  /// Smoothing rounds. After each round but the last, the matching is re-chosen as the straightest one (5.1) for
  /// the smoothed frames (a right-hand-side update, no refactorization) and the system is solved again.
  int smoothing_rounds = 2;
  /// Split singularities of |quarter index| >= split_min_quarters into quarter-index branch points on nearby
  /// vertices (field/singularity_split.h), then smooth once more with that matching. A whole-turn singularity
  /// (index ±1, e.g. at the apexes of a high-valence bipyramid) is invisible to the 4-sheeted cover and folds the
  /// parameterization flat (998 of 1000 triangles flipped on a valence-500 bipyramid; 0 after the split).
  bool split_singularities = true;
  /// Default 4 (whole turns only): the shipped meshes have none, and splitting the |q| = 2, 3 cones of cow and
  /// mech_holes_shark as well (value 2) raises their E_D + E_H by 20% and ARAP by 25% (BENCHMARKS.md, Robustness).
  int split_min_quarters = 4;
};

/// Presets of the field stage for the commands and the Python module.
enum class FieldStyle {
  /// The defaults above: curvature-guided (thesis ch. 5), trusted frames pulled to the principal directions.
  Curvature,
  /// The smoothest cross field with a weak pull to the curvature directions (λ = 1, fill_alignment = 0.1), as
  /// MIQ / Directional users know it; features stay fixed. Lower distortion on organic shapes: bunny_3k at the
  /// Table 7.1 density, ARAP 0.0171 -> 0.0117 and RSD edge / angle 11.2 / 7.8 -> 9.2 / 6.7 % (BENCHMARKS.md).
  Smooth,
};
/// Parses "curvature|smooth". \throw InputError otherwise.
FieldStyle parse_field_style(std::string_view name);
std::string to_string(FieldStyle style);  ///< \pre none
/// The FieldOptions of a preset. \pre none
FieldOptions field_options(FieldStyle style);

/// The frame field and what it was made from.
struct FrameFieldResult {
  FrameField field;               ///< cross field (Y = iX) with its matching
  CurvatureFrames curvature;      ///< principal curvature frames (5.1.1)
  Eigen::VectorXd stability;      ///< #F, ω_t (5.2)
  std::vector<char> trusted;      ///< #F, faces of the alignment terms / propagation sources
  std::vector<char> constrained;  ///< #F, feature-aligned faces (fixed during smoothing)
  std::vector<BranchPoint> branch_points;
  std::vector<QuarterMove> singularity_moves;  ///< quarters moved by the split (FieldOptions::split_singularities)
  double energy_smooth_initial = 0;            ///< E_S of the filled field with its straightest matching
  double energy_smooth = 0;                    ///< E_S of the result
  double energy_align = 0;                     ///< E_A of the result's rotation angles
};

/// Runs thesis Chapter 5 with the options' defaults documented above.
/// \pre mesh is a valid triangle mesh. \throw NumericalError if the smoothing system cannot be factored.
/// Honours progress.cancelled() between stages (returns the field reached so far, always a complete field).
FrameFieldResult compute_frame_field_detailed(const Mesh& mesh, const FieldOptions& options = {},
                                              ProgressSink& progress = null_progress());

/// Frame field guided by principal curvature (thesis 5.1); see FieldOptions for the defaults.
/// \pre and \throw as compute_frame_field_detailed.
FrameField compute_frame_field(const Mesh& mesh, const FieldOptions& options = {},
                               ProgressSink& progress = null_progress());

}  // namespace quadcover
