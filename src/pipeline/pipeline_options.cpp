#include "pipeline/pipeline_options.h"

#include <sstream>

#include "common/errors.h"

namespace quadcover {

void validate(const PipelineOptions& o) {
  const ParamOptions& p = o.param;
  if (o.split_min_quarters < 2)
    throw InputError("split_cones", 0, "must be >= 2 (2 = every half cone, 4 = whole turns only)");
  if (p.density.edge_length < 0) throw InputError("edge_length", 0, "must be > 0 (0 = default density)");
  if (p.density.target_quads < 0) throw InputError("quads", 0, "must be > 0 (0 = default density)");
  if (p.density.edge_length > 0 && p.density.target_quads > 0)
    throw InputError("edge_length/quads", 0, "give either an edge length or a quad count, not both");
  if (p.stiffening.max_iterations < 0) throw InputError("stiffening", 0, "must be >= 0 (0 = off)");
  if (o.fold_refinement_rounds < 0) throw InputError("fold_refinement", 0, "must be >= 0 (0 = off)");
  if (o.validity_retries < 0 || o.validity_retries > 8)
    throw InputError("validity_retries", 0, "must be in [0, 8] (0 = off)");
  if (p.relaxation.iterations < 0) throw InputError("relaxation", 0, "must be >= 0 (0 = off)");
  if (o.max_evaluations < kAutoBudget)
    throw InputError("max_iterations", 0, "must be >= -1 (-1 = auto, 0 = until converged)");
  if (o.smoothing.iterations < 0) throw InputError("smooth_quads", 0, "must be >= 0 (0 = off)");
  if (!(o.smoothing.rigidity >= 0 && o.smoothing.rigidity <= 1))
    throw InputError("smooth_rigidity", 0, "must be in [0, 1]");
  if (!(o.square_hole_grid_units >= 0)) throw InputError("square_holes", 0, "must be >= 0 (0 = off)");
  const double angle = p.features.sharp_angle_degrees;
  if (!(angle >= 0 && angle <= 180)) {
    std::ostringstream got;
    got << angle;
    throw InputError("feature_angle", 0, "must be in [0, 180] degrees (0 = no sharp features), got " + got.str());
  }
}

FieldOptions field_stage_options(const PipelineOptions& options) {
  FieldOptions o = field_options(options.field_style);
  o.features = options.param.features;
  o.fill = options.fill;
  o.split_min_quarters = options.split_min_quarters;
  return o;
}

OptimizeOptions optimize_stage_options(const PipelineOptions& options, const ParamOptions& param) {
  OptimizeOptions o;
  o.mode = options.optimize;
  o.lambda = field_stage_options(options).lambda;
  o.max_evaluations = options.max_evaluations;
  o.param = param;
  return o;
}

}  // namespace quadcover
