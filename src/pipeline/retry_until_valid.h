#pragma once
// The loop of the validity retries (pipeline/validity_retries.h), shared by the param and the remesh job.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "common/progress.h"
#include "common/seconds_since.h"
#include "pipeline/parameterize_mesh.h"
#include "pipeline/validity_retries.h"

namespace quadcover {

/// A shape thinner than the default quad edge (a thin tube, a narrow strip: the default h is twice the mean edge
/// length, param/density.h) folds most of its map at the default density, or leaves too few quads to extract. Such
/// a first attempt (non-positive triangles and triangles the fold refinement added, pipeline/fold_refinement.h, more
/// than kUnderResolvedShare of the input's triangles together, while the map holds fewer quads than the input has
/// triangles: a triangulation coarser than the grid folds for other reasons; or DensityTooCoarse) is made
/// again with the default edge factor halved, up to kCoarseHalvings times; the kept job says so in a warning. A
/// density the user gave is never changed, and with no validity retries (`once_retries` 0) attempt 0 is kept.
inline constexpr int kCoarseHalvings = 5;
inline constexpr double kUnderResolvedShare = 0.25;

/// Attempt 0 of retry_until_valid with the halvings above, and its Validity by `judge`. When a finer attempt is
/// refused (the memory budget, pipeline/memory_budget.h), the coarser one is kept and a warning says why.
/// \throw as run (DensityTooCoarse after the last halving).
template <class Run, class Judge>
auto first_attempt(const PipelineOptions& once, int once_retries, Run& run, Judge& judge, ProgressSink& progress) {
  const DensityOptions& density = once.param.density;
  const bool adjustable = density.edge_length <= 0 && density.target_quads <= 0 && once_retries > 0;
  PipelineOptions o = once;
  using Judged = std::pair<decltype(run(once)), Validity>;
  std::optional<Judged> coarser;  // the attempt before, while a finer one runs
  for (int halvings = 0;; ++halvings) {
    const bool last = !adjustable || halvings == kCoarseHalvings || progress.skip_improvements();
    std::string why;
    try {
      auto job = run(o);
      const Validity v = judge(job);
      const int faces = static_cast<int>(param_job(job).map.uv.rows()) - param_job(job).refinement.added_faces;
      const int added = param_job(job).fold_refinement.added_faces, trouble = v.non_positive + added;
      if (last || trouble <= kUnderResolvedShare * faces || map_quads(param_job(job).map) >= faces) {
        if (halvings > 0)
          param_job(job).warnings.push_back(
              "the default density was too coarse for this shape (a part thinner than the quad edge): made " +
              std::to_string(1 << (2 * halvings)) + " times finer, h = " +
              std::to_string(param_job(job).map.edge_length) + " (pass --faces or --edge-length to choose)");
        return Judged{std::move(job), v};
      }
      why = std::to_string(v.non_positive) + " of " + std::to_string(faces) + " triangles folded, " +
            std::to_string(added) + " added around folds";
      coarser.emplace(std::move(job), v);
    } catch (const InputError& e) {
      const bool too_coarse = dynamic_cast<const DensityTooCoarse*>(&e) != nullptr;
      if (!coarser && (last || !too_coarse)) throw;
      if (coarser) {
        param_job(coarser->first)
            .warnings.push_back(std::string("the default density is too coarse for this shape, and ") +
                                "a finer one was refused: " + e.what());
        return std::move(*coarser);
      }
      why = e.what();
    }
    o.param.density.default_edge_factor /= 2;
    progress.report("retry", -1, "default density too coarse (" + why + "): attempt at half the quad edge");
  }
}

/// FieldStyle::Auto's fallback: when the first attempt ran with the Smooth field (a closed surface) and is not valid
/// (wrong windings too), the job runs once more with the Curvature field, whose cones sit elsewhere (on CAD parts
/// such as couplingdown_genus9 the smoothest field leaves 8 wrong windings, the curvature-guided one 2). Retries
/// on (validity_retries > 0) and no time limit or Ctrl-C reached. \pre none
inline bool fall_back_to_curvature(const PipelineOptions& given, FieldStyle first_style, const Validity& first,
                                   ProgressSink& progress) {
  return given.field_style == FieldStyle::Auto && first_style == FieldStyle::Smooth && !first.valid() &&
         given.validity_retries > 0 && !progress.skip_improvements();
}

/// Attempt 0 = first_attempt(given minus its retries), then FieldStyle::Auto's fallback (fall_back_to_curvature),
/// kept when more valid, then, while the best so far is worth_retrying, up to
/// given.validity_retries further attempts run(attempt_options(given, h0, k)), keeping the best by `judge`. The
/// kept job's ParamJob (param_job(job)) records the attempts; a warning says when the kept one is not the first or
/// is not valid. A time limit or Ctrl-C ends the retries (recorded as cut short).
/// \throw InputError for invalid options (validate).
template <class Run, class Judge>
auto retry_until_valid(const PipelineOptions& given, Run run, Judge judge, ProgressSink& progress) {
  validate(given);
  PipelineOptions once = given;
  once.validity_retries = 0;
  SteadyClock::time_point start = SteadyClock::now();
  auto [first, best_validity] = first_attempt(once, given.validity_retries, run, judge, progress);
  using Job = decltype(first);
  const FieldStyle first_style = param_job(first).options.field_style;
  std::vector<ValidityAttempt> attempts{
      {1.0, param_job(first).map.edge_length, best_validity, first_style, seconds_since(start)}};
  int used = 0;
  Job best = std::move(first);
  if (fall_back_to_curvature(given, first_style, best_validity, progress)) {
    progress.report("retry", -1, "result not valid: the map made again from the curvature-guided field");
    PipelineOptions curvature = once;
    curvature.field_style = FieldStyle::Curvature;
    try {
      start = SteadyClock::now();
      auto [next, v] = first_attempt(curvature, given.validity_retries, run, judge, progress);
      attempts.push_back({1.0, param_job(next).map.edge_length, v, FieldStyle::Curvature, seconds_since(start)});
      if (v < best_validity) best = std::move(next), best_validity = v, used = 1;
    } catch (const InputError& e) {  // e.g. too coarse a density for that field: the smooth field's result stays
      param_job(best).warnings.push_back(std::string("the map from the curvature-guided field, tried because this ") +
                                         "one is not valid, could not be made: " + e.what());
    }
  }
  // The density retries keep the field of the best so far, and its density made finer for a loop (their h is
  // explicit: the job would not say why).
  const LoopDensityRaise raised = param_job(best).density.raised;
  PipelineOptions retried = given;
  retried.field_style = param_job(best).options.field_style;
  const double h0 = param_job(best).options.param.density.edge_length;
  const int field_attempts = static_cast<int>(attempts.size()) - 1;
  for (int k = 1; k <= given.validity_retries && best_validity.worth_retrying(); ++k) {
    if (progress.skip_improvements()) {
      record_cut_short(param_job(best), "validity retries");
      break;
    }
    progress.report("retry", -1, "result not valid: attempt " + std::to_string(k + 1) + " at a nearby density");
    start = SteadyClock::now();
    Job next = run(attempt_options(retried, h0, k));
    param_job(next).density.raised = raised;
    const Validity v = judge(next);
    attempts.push_back({attempt_quads_factor(k, given.param.density), param_job(next).map.edge_length, v,
                        retried.field_style, seconds_since(start)});
    if (v < best_validity) best = std::move(next), best_validity = v, used = k + field_attempts;
  }
  ParamJob& kept = param_job(best);
  kept.field_style_auto = given.field_style == FieldStyle::Auto;
  kept.validity_attempts = attempts;
  kept.validity_attempt_used = used;
  kept.options.validity_retries = given.validity_retries;  // the attempts ran without; the job had these
  if (kept.density.raised.loop > 0)
    kept.warnings.insert(kept.warnings.begin(), loop_density_warning(kept.density.raised));
  if (used > 0 || !best_validity.valid()) kept.warnings.push_back(validity_warning(attempts, used));
  return best;
}

}  // namespace quadcover
