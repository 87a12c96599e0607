#pragma once
// The parameterization job: frame field (thesis ch. 5) → default density → Algorithm 6.1 (ch. 6) → keep-better →
// QuadCover parameterization (ch. 2-4). One call for the CLI's `param`, the Python module and the benches.
#include <Eigen/Core>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "common/progress.h"
#include "common/stage_meter.h"
#include "field/frame_field.h"
#include "mesh/mesh.h"
#include "param/parameterization.h"
#include "pipeline/curve_refinement.h"
#include "pipeline/fold_refinement.h"
#include "pipeline/pipeline_options.h"
#include "pipeline/validity_retries.h"

namespace quadcover {

/// The default density made finer for a short boundary loop (param/density.h LoopResolution), as the report and the
/// warning name it.
struct LoopDensityRaise {
  int loop = 0;    ///< the loop's number as in the report's boundary_loops (0: the density was not made finer)
  bool rim = false;  ///< loop is instead the number of a hole rim (DensityOptions::hole_rims, from 1)
  int vertex = 0;  ///< its lowest vertex, 1-based as in the file
  Eigen::Vector3d at = Eigen::Vector3d::Zero();  ///< that vertex's position
  double length = 0;                             ///< the loop's length in model units
  double quads_factor = 1;                       ///< the quads of the finer density over the coarser one's
  double grid_units = 0;                         ///< the quad edges around the loop asked for
};

/// The warning for a raised density (raise.loop > 0). \pre none
std::string loop_density_warning(const LoopDensityRaise& raise);

/// How the job met a requested quad count N (DensityOptions::target_quads): the map's h is set so that its free map
/// (before rounding) has N expected faces (param/face_count.h expected_face_count: Σ|area(φ(t))|, plus half the
/// boundary's length in grid units where it cuts cells); the rounding moves that count a little, and while it is off
/// by more than kDensityTolerance the map is solved again at a corrected h (count ≈ c / h², interpolated between tries
/// below and above N), at most kDensityResolves times, keeping the closest.
struct DensityReport {
  int target_quads = 0;    ///< N asked for (0: an edge length or the default density)
  double first_quads = 0;  ///< expected face count of the first map
  double quads = 0;        ///< expected face count of the final map
  int resolves = 0;        ///< maps solved again at a corrected edge length
  LoopDensityRaise raised;  ///< the default density made finer for a boundary loop; kept by the density retries
};
inline constexpr double kDensityTolerance = 0.02;
inline constexpr int kDensityResolves = 4;

struct ParamJob {
  /// As given, with the default density fixed to an explicit edge length and FieldStyle::Auto resolved for the
  /// input (resolved_field_style; field_style_auto says it was).
  PipelineOptions options;
  bool field_style_auto = false;
  /// The triangulation the map lives on: the input's, or a refinement of it (more triangles, the input's vertices
  /// first) when the curve constraints, the field's singularities (pipeline/cone_refinement.h) or the fold
  /// refinement needed one; `split` lists the curve refinement's splits, then the cone refinement's, then the fold
  /// refinement's. Use mesh(input) for it.
  CurveRefinement refinement;
  int cone_splits = 0;                   ///< the entries of refinement.split that the cone refinement made
  FoldRefinementReport fold_refinement;  ///< what the fold refinement did (pipeline/fold_refinement.h)
  FrameField field;             ///< the field the map was made from (optimized or original, see optimize["kept"])
  int field_branch_points = 0;  ///< branch points of the field stage's field, before the optimization
  /// Quarters the field stage moved to split singularities of |index| >= 1/2 (FieldOptions::split_min_quarters).
  int field_singularity_moves = 0;
  /// Sharp edges the field followed only as crisp short creases (FeatureOptions::crisp_crease_degrees).
  int crisp_creases = 0;
  /// Opposite branch point pairs cancelled before the map (PipelineOptions::cancel_close_cones): in Algorithm 6.1's
  /// field, or in the field stage's with OptimizeMode::None (options.optimize says which).
  int cancelled_close_pairs = 0;
  Parameterization map;
  nlohmann::json optimize;            ///< the "optimize" object (optimize/optimize_field.h to_json, plus "kept")
  DensityReport density;              ///< how a requested quad count was met
  /// Branch point pairs on one lattice point merged into one cone, and the maps solved again for that
  /// (pipeline/cone_merging.h).
  int merged_cone_pairs = 0, merge_rounds = 0;
  /// Branch points of fake cone pairs moved to the vertex the map winds around, and the maps solved again for that
  /// (pipeline/cone_merging.h wound_cone_moves).
  int moved_wound_cones = 0, wound_cone_rounds = 0;
  /// The map made again with the close cones on one point set apart (PipelineOptions::separate_coincident_cones):
  /// whether it was tried and kept, and how valid it came out (non_positive, wrong_windings).
  struct ConeSeparation {
    bool tried = false, kept = false;
    Validity validity;
  } cone_separation;
  std::vector<std::string> warnings;  ///< degraded results, in sentences (the CLI prints them on stderr)
  /// The improving stages (ProgressSink::skip_improvements) a Ctrl-C or time limit skipped or cut short, in job
  /// order; the result is complete and checked, but a full run would improve it (the CLI exits with 3 then).
  std::vector<std::string> cut_short;
  /// The runs of the job at nearby densities while the result was not valid (pipeline/validity_retries.h): the
  /// first is this job's own when no retry ran; validity_attempt_used is the one kept.
  std::vector<ValidityAttempt> validity_attempts;
  int validity_attempt_used = 0;
  StageSeconds seconds;     ///< per stage (common/stage_meter.h)
  StagePeakBytes peak_bytes;  ///< per stage, under the names of `seconds`

  /// The mesh of `map`: the refined one, or `input` (the mesh given to parameterize_mesh) when none was needed.
  /// \pre input is the mesh given to parameterize_mesh.
  const Mesh& mesh(const Mesh& input) const { return refinement.mesh ? *refinement.mesh : input; }
};

/// The ParamJob of a job (for the validity retries). \pre none
inline ParamJob& param_job(ParamJob& job) { return job; }

/// Runs the parameterization job on `mesh`, again at nearby densities while the map is not valid
/// (options.validity_retries, pipeline/validity_retries.h).
/// \pre mesh is a valid triangle mesh (build_mesh).
/// \throw InputError for invalid options (validate()) or a density the memory cannot hold (check_memory_budget),
/// NumericalError if a factorization fails.
/// Honours progress.cancelled(): Algorithm 6.1 stops with its best field; the map is still completed, the
/// improving stages after it are skipped or cut short (listed in ParamJob::cut_short, with a warning).
ParamJob parameterize_mesh(const Mesh& mesh, const PipelineOptions& options, ProgressSink& progress = null_progress());

/// A check of the job's first map (before the cone moves, density and fold refinement, which keep its parameter
/// area), e.g. that a remesh has quads to extract; it throws to refuse the job before those stages.
using FirstMapCheck = std::function<void(const Mesh&, const Parameterization&)>;

/// One attempt of the job at the density of `options`, without the validity retries (the remesh job retries
/// itself as a whole), with `check` (if any) on the first map. \pre, \throw as parameterize_mesh, and what
/// `check` throws.
ParamJob parameterize_once(const Mesh& mesh, const PipelineOptions& options, ProgressSink& progress,
                           const FirstMapCheck& check = {});

/// The density stage of the job (see DensityReport): re-solves job.map from job.field when it misses `target_quads`
/// (> 0; 0: nothing to hit) by more than 2 %. \pre job = parameterize_mesh(mesh, …).
/// \throw NumericalError if a factorization fails.
DensityReport hit_target_count(const Mesh& mesh, ParamJob& job, ProgressSink& progress, int target_quads);

/// Appends `stage` to job.cut_short and keeps its one warning in job.warnings ("stopped (Ctrl-C or time limit) ...:
/// skipped or cut short: STAGES; ...") up to date. \pre none
void record_cut_short(ParamJob& job, std::string stage);

/// The warnings a map deserves (handles whose field has holonomy but no branch points, even branch points left on
/// half-integers), in the words the CLI prints. \pre none
std::vector<std::string> map_warnings(const Parameterization& map);

}  // namespace quadcover
