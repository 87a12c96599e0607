#pragma once
// The parameterization job: frame field (thesis ch. 5) → default density → Algorithm 6.1 (ch. 6) → keep-better →
// QuadCover parameterization (ch. 2-4). One call for the CLI's `param`, the Python module and the benches.
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "common/progress.h"
#include "field/frame_field.h"
#include "mesh/mesh.h"
#include "param/parameterization.h"
#include "pipeline/pipeline_options.h"

namespace quadcover {

/// Wall-clock seconds per stage, in pipeline order.
using StageSeconds = std::vector<std::pair<std::string, double>>;

struct ParamJob {
  PipelineOptions options;      ///< as given, with the default density fixed to an explicit edge length
  FrameField field;             ///< the field the map was made from (optimized or original, see optimize["kept"])
  int field_branch_points = 0;  ///< branch points of the field stage's field, before the optimization
  Parameterization map;
  nlohmann::json optimize;            ///< the "optimize" object (optimize/optimize_field.h to_json, plus "kept")
  std::vector<std::string> warnings;  ///< degraded results, also sent to progress as "warning: ..."
  StageSeconds seconds;
};

/// Runs the parameterization job on `mesh`.
/// \pre mesh is a valid triangle mesh (build_mesh).
/// \throw InputError for invalid options (validate()), NumericalError if a factorization fails.
/// Honours progress.cancelled(): Algorithm 6.1 stops with its best field; the map is still completed.
ParamJob parameterize_mesh(const Mesh& mesh, const PipelineOptions& options, ProgressSink& progress = null_progress());

/// The warnings a map deserves (handles whose field has holonomy but no branch points, even branch points left on
/// half-integers), in the words the CLI prints.
std::vector<std::string> map_warnings(const Parameterization& map);

}  // namespace quadcover
