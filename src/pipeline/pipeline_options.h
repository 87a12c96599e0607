#pragma once
// Options of the whole jobs (parameterize a mesh, remesh it): one struct per stage, gathered once, so that the CLI,
// the Python module and the benches run the same pipeline with the same defaults and the same checks.
#include <cstdint>
#include <string>

#include "field/compute_frame_field.h"
#include "optimize/optimize_field.h"
#include "param/parameterize.h"
#include "quad/extract_quads.h"
#include "quad/smooth_quads.h"

namespace quadcover {

struct PipelineOptions {
  /// Field stage preset (field/compute_frame_field.h): curvature-guided (thesis ch. 5), smoothest, or chosen per
  /// surface (Auto: resolved_field_style, and the fallback of pipeline/retry_until_valid.h).
  FieldStyle field_style = FieldStyle::Auto;
  /// The field stage splits its singularities of |quarter index| >= this into quarter-index ones (>= 2;
  /// FieldOptions::split_min_quarters).
  int split_min_quarters = FieldOptions{}.split_min_quarters;
  /// Frames of the untrusted faces before the smoothing (FieldOptions::fill): the power-field solve, or the
  /// thesis's trusted propagation (5.1.2).
  Fill fill = Fill::Smooth;
  /// Optimization of the field's matching (thesis ch. 6, optimize/optimize_field.h).
  OptimizeMode optimize = OptimizeMode::Relocate;
  /// E_D evaluations of Algorithm 6.1: kAutoBudget (-1) = auto, 0 = until converged.
  long max_evaluations = kAutoBudget;
  /// Also parameterize the original field and keep the map with the lower E_D + E_H (parameterize_keep_better).
  bool keep_better = true;
  /// Split the edges where the curve constraints would hold a triangle at zero area (pipeline/curve_refinement.h);
  /// the map then lives on a finer triangulation (ParamJob::mesh).
  bool refine_curve_triangles = false;
  /// Closed crease loops shorter than this many quad edges h of the density asked for (target_edge_length) and
  /// straight on one side are followed on that side only (FeatureOptions::free_short_loops_below,
  /// field/crease_loops.h): small holes through a part come out square in an even grid (BENCHMARKS.md, "Short
  /// crease loops as square holes"). 0 = off.
  double square_hole_grid_units = 8.0;
  /// Before the map: cancel the branch point pairs of opposite index closer than one quad edge h along the mesh
  /// edges (close_opposite_cone_merges, pipeline/cone_merging.h) in the field the map is meant to be made from:
  /// Algorithm 6.1's, or the field stage's with OptimizeMode::None (keep-better compares the optimized field with
  /// the field stage's as it is). The rounding puts every cone on a lattice point, so such a pair lands on one point
  /// or on neighbouring ones and the map folds or winds wrong between them (BENCHMARKS.md, "Close opposite cones
  /// cancelled").
  bool cancel_close_cones = true;
  /// Merge branch point pairs that the map puts on one lattice point into one cone and solve the map again
  /// (pipeline/cone_merging.h).
  bool merge_coincident_cones = true;
  /// Move the branch point of each fake cone pair (a cone wound one turn off next to a vertex wound the opposite
  /// turn) to that vertex and solve the map again, kept while the map gets more valid (pipeline/cone_merging.h).
  bool move_wound_cones = true;
  /// When the result is not valid beside branch points the rounding put on one lattice point (a few edges apart),
  /// make the map again with those cones set apart by re-rounded periods (ParamOptions::separate_close_cones,
  /// param/cone_separation.h), kept when more valid.
  bool separate_coincident_cones = true;
  /// Rounds of the refinement around the triangles the untangling leaves non-positive (pipeline/fold_refinement.h;
  /// 0 = off); the map then lives on a finer triangulation (ParamJob::mesh).
  int fold_refinement_rounds = 6;
  /// Runs of the whole job again at nearby densities while the result is not valid (pipeline/validity_retries.h;
  /// 0 = off).
  int validity_retries = 1;
  /// Density, lattice, rounding, relaxation, stiffening, curve alignment (param/parameterize.h). Its `features`
  /// (the feature angle: sharp_angle_degrees, 0 = no sharp features; boundaries) are the curves of both the field
  /// stage (field_stage_options) and the alignment of the map, so the two always follow the same curves.
  ParamOptions param;
  /// Remesh only: extraction and tangential smoothing of the quad mesh.
  ExtractOptions extraction;
  QuadSmoothingOptions smoothing;
  /// Memory the job may use, in bytes (0 = the machine's available memory): a density whose estimated peak exceeds
  /// it is refused before any work (pipeline/memory_budget.h).
  std::int64_t max_memory_bytes = 0;
};

/// Checks every option a user can set, naming it as the Python keyword (the CLI validates its flags first).
/// \throw InputError for a contradictory or out-of-range option (both edge_length and quads, negative counts,
/// rigidity outside [0, 1], a budget below -1, a feature angle outside [0, 180]).
void validate(const PipelineOptions& options);

/// The FieldOptions of the field stage (the preset with options.fill and options.param.features), whose λ also serves
/// Algorithm 6.1's re-smoothing. \pre none
FieldOptions field_stage_options(const PipelineOptions& options);

/// The OptimizeOptions of the optimization stage (mode, budget, λ of the field stage, `param` for E_H). \pre none
OptimizeOptions optimize_stage_options(const PipelineOptions& options, const ParamOptions& param);

}  // namespace quadcover
