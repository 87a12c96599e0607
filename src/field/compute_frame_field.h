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

/// How the frames of the untrusted faces are obtained before smoothing (`--fill`).
enum class Fill {
  /// Thesis 5.1.2 (trusted propagation): breadth-first parallel transport from the trusted faces. Seams where
  /// propagated regions meet leave spurious branch points that the fixed-matching smoothing (5.3) cannot remove.
  Propagate,
  /// Global smooth solve of the power field u = X^4 (field/power_field.h) aligned to the trusted curvature
  /// directions with weight ω_t^stable (5.2) and exactly to the constrained faces; its matching is then the
  /// straightest one (5.1) and the thesis smoothing (5.3) runs on top.
  Smooth,
};
/// Parses "propagate|smooth". \throw InputError otherwise.
Fill parse_fill(std::string_view name);
std::string to_string(Fill fill);  ///< "propagate" or "smooth". \pre none

/// Options of the field stage. Measurements behind the defaults: BENCHMARKS.md, "Frame field".
struct FieldOptions {
  CurvatureOptions curvature;  ///< estimator of the principal curvature frames (default HP)
  FeatureOptions features;     ///< boundary / sharp-edge alignment (default on, 35°)
  /// Fraction of faces whose curvature frames are trusted (5.1.2); the thesis recommends 10-30%.
  double trusted_fraction = 0.2;
  /// Frames of the untrusted faces: the power-field solve (fewer branch points) or the thesis's propagation.
  Fill fill = Fill::Smooth;
  /// Fill::Smooth: alignment strength μ of PowerFieldProblem. Larger values follow the curvature frames more
  /// closely at the price of curl (E_D) and eventually branch points.
  double fill_alignment = 1000.0;
  /// Fill::Smooth: Ginzburg–Landau weight σ and majorize-minimize steps of PowerFieldProblem (σ = 1000: core
  /// radius ≈ 3% of √area); they remove close ± pairs and make |u| ≈ 1.
  double fill_unit_weight = 1000.0;
  int fill_iterations = 10;
  /// λ of (5.3) in (0, 1]: 1 ignores the curvature directions (only fixed faces anchor the field), small values
  /// keep trusted frames at their curvature directions (with Fill::Smooth, E_A measures the rotation from the
  /// filled frame to the nearest curvature direction: FrameSmoother::set_alignment_targets). 0.5 weighs the
  /// (scale-normalized) terms equally.
  double lambda = 0.5;
  /// Smoothing rounds. After each round but the last, the matching is re-chosen as the straightest one (5.1) for
  /// the smoothed frames (a right-hand-side update, no refactorization) and the system is solved again.
  int smoothing_rounds = 2;
  /// Split singularities of |quarter index| >= split_min_quarters into quarter-index branch points on nearby
  /// vertices (field/singularity_split.h), then smooth once more with that matching. A whole-turn singularity
  /// (index ±1) is invisible to the 4-sheeted cover and folds the parameterization flat.
  bool split_singularities = true;
  /// Default 2: every singularity of the split field has |q| = 1 (valence 3 or 5). A +3/4 cone (angle π/2) is one
  /// quad corner, a vertex of valence 1 that no quad mesh holds (the extraction cut it out as a spike); a +1/2 cone
  /// is a valence-2 vertex (a doublet) and a -1/2 cone a valence-6 one (BENCHMARKS.md, "Half and three-quarter cones
  /// split"). 4 splits whole turns only.
  int split_min_quarters = 2;
};

/// Presets of the field stage for the commands and the Python module (`--field`).
enum class FieldStyle {
  /// The defaults above: the power fill aligned to the trusted principal curvature directions, then the
  /// smoothing (5.3) pulling the trusted frames towards them.
  Curvature,
  /// The smoothest cross field with a weak pull to the curvature directions (λ = 1, fill_alignment = 0.1), as
  /// MIQ / Directional users know it; features stay fixed. Lower distortion on organic shapes.
  Smooth,
  /// Chosen per surface by resolved_field_style: Smooth on a closed surface, Curvature on one with a boundary.
  Auto,
};
/// Parses "auto|curvature|smooth". \throw InputError otherwise.
FieldStyle parse_field_style(std::string_view name);
std::string to_string(FieldStyle style);  ///< \pre none
/// The FieldOptions of a preset. \pre style is not Auto (resolved_field_style) \throw std::logic_error for Auto
FieldOptions field_options(FieldStyle style);
/// `style`, with Auto resolved for `mesh`: Smooth when the mesh has no boundary, else Curvature. On closed shapes
/// the smoothest field has less distortion (lower ARAP on 11 of the 14 closed shipped meshes); along boundaries the
/// curvature-guided one leaves fewer non-quads at holes (BENCHMARKS.md, "Field chosen per surface"). The jobs make
/// the map from the Curvature field too when the Smooth one's is not valid (pipeline/retry_until_valid.h).
/// \pre none
FieldStyle resolved_field_style(FieldStyle style, const Mesh& mesh);

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
