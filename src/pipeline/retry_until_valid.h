#pragma once
// The loop of the validity retries (pipeline/validity_retries.h), shared by the param and the remesh job.
#include <cstdio>
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

/// A shape thinner than the default quad edge (a thin tube or handle, a narrow strip: the default h is twice the mean
/// edge length, param/density.h) folds most of its map at the default density, leaves too few quads to extract, or
/// gives a quad mesh that falls apart there. Such a first attempt (see under_resolved; or DensityTooCoarse) is made
/// again with the default edge factor halved, up to kCoarseHalvings times; the kept job says so in a warning. A
/// density the user gave is never changed, and with no validity retries (`once_retries` 0) attempt 0 is kept.
inline constexpr int kCoarseHalvings = 5;
inline constexpr double kUnderResolvedShare = 0.25;

/// Why a job at the default density is made again at half its quad edge, or "" when it is not: non-positive
/// triangles and triangles the fold refinement added (pipeline/fold_refinement.h) more than kUnderResolvedShare of
/// the input's triangles together, or a quad mesh whose components, genus or boundary loops differ from the input's;
/// either only while the map holds fewer quads than the input has triangles (a triangulation coarser than the grid
/// folds, and a finer grid does not mend what the triangles cannot resolve). \pre none
template <class Job>
std::string under_resolved(Job& job, const Validity& v) {
  const ParamJob& p = param_job(job);
  const int faces = static_cast<int>(p.map.uv.rows()) - p.refinement.added_faces;
  if (map_quads(p.map) >= faces) return "";
  const int added = p.fold_refinement.added_faces;
  if (v.non_positive + added > kUnderResolvedShare * faces)
    return std::to_string(v.non_positive) + " of " + std::to_string(faces) + " triangles folded, " +
           std::to_string(added) + " added around folds";
  if (v.topology_changes > 0) return "the quad mesh's topology differs from the input's";
  return "";
}

/// The warning of a job made `halvings` times at half the default quad edge factor (none for 0): how many times more
/// quads its h gives than `first_h`, the first attempt's (the factor of 4 per halving, unless the branch points' bound
/// of the default h held it finer already; 4 per halving when attempt 0 gave no map, first_h 0). \pre halvings >= 0
template <class Job>
void say_made_finer(Job& job, int halvings, double first_h) {
  ParamJob& p = param_job(job);
  const double ratio =
      first_h > 0 ? (first_h / p.map.edge_length) * (first_h / p.map.edge_length) : 1 << (2 * halvings);
  if (halvings == 0 || ratio < 1.01) return;  // the same h as attempt 0: nothing was made finer
  char factor[32];
  std::snprintf(factor, sizeof factor, "%.3g", ratio);
  p.warnings.push_back("the default density was too coarse for this shape (a part thinner than the quad edge): made " +
                       std::string(factor) + " times finer, h = " + std::to_string(p.map.edge_length) +
                       " (pass --faces or --edge-length to choose)");
}

/// Attempt 0 of retry_until_valid with the halvings above, and its Validity by `judge`: the most valid of the
/// attempts made (the finer one on a tie). When a finer attempt is refused (the memory budget,
/// pipeline/memory_budget.h), the best before it is kept and a warning says why.
/// \throw as run (DensityTooCoarse after the last halving).
template <class Run, class Judge>
auto first_attempt(const PipelineOptions& once, int once_retries, Run& run, Judge& judge, ProgressSink& progress) {
  const DensityOptions& density = once.param.density;
  const bool adjustable = density.edge_length <= 0 && density.target_quads <= 0 && once_retries > 0;
  PipelineOptions o = once;
  using Judged = std::pair<decltype(run(once)), Validity>;
  std::optional<Judged> best;  // while a finer attempt runs
  int best_halvings = 0;
  double first_h = 0;  // the h of attempt 0
  for (int halvings = 0;; ++halvings) {
    const bool last = !adjustable || halvings == kCoarseHalvings || progress.skip_improvements();
    std::string why;
    try {
      auto job = run(o);
      if (halvings == 0) first_h = param_job(job).map.edge_length;
      const Validity v = judge(job);
      why = last ? "" : under_resolved(job, v);
      if (!best || !(best->second < v)) best.emplace(std::move(job), v), best_halvings = halvings;
      if (why.empty()) break;
    } catch (const InputError& e) {
      const bool too_coarse = dynamic_cast<const DensityTooCoarse*>(&e) != nullptr;
      if (!best && (last || !too_coarse)) throw;
      if (best) {
        param_job(best->first)
            .warnings.push_back(std::string("the default density is too coarse for this shape, and ") +
                                "a finer one was refused: " + e.what());
        break;
      }
      why = e.what();
    }
    o.param.density.default_edge_factor /= 2;
    progress.report("retry", -1, "default density too coarse (" + why + "): attempt at half the quad edge");
  }
  say_made_finer(best->first, best_halvings, first_h);
  return std::move(*best);
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

/// The fallback for creases finer than the density: when the best result so far is still not valid and its field
/// followed crisp short creases (FeatureOptions::crisp_crease_degrees; ParamJob::crisp_creases), the job runs once
/// more following the long crease chains alone. Creases a quad or two long crowd the field's cones (a coarse gear's
/// teeth at a few hundred quads wound the map wrong at 11 vertices); crisp_min_length keeps those shorter than a
/// requested quad edge out, this catches the rest. With retries on and no time limit or Ctrl-C reached. \pre none
inline bool fall_back_to_long_chains(const PipelineOptions& given, const Validity& best, int crisp_creases,
                                     ProgressSink& progress) {
  return crisp_creases > 0 && !best.valid() && given.validity_retries > 0 && !progress.skip_improvements();
}

/// The largest map (triangles) that fall_back_to_full_optimization makes again.
inline constexpr int kFullFallbackMaxFaces = 30000;

/// The second fallback: when the best result so far is still not valid and Algorithm 6.1 ran in its default mode
/// (relocate: moves the field's branch points), the job runs once more with the full optimization (creation, then
/// balancing), whose cones sit elsewhere: on spot and mech_holes_shark at 6500 vertices its map is valid where
/// relocate's winds wrong (BENCHMARKS.md, "The full optimization when the map is not valid"). Only on maps of at
/// most kFullFallbackMaxFaces triangles (where it fails it costs one or two more jobs), with retries on and no time
/// limit or Ctrl-C reached. \pre none
inline bool fall_back_to_full_optimization(const PipelineOptions& given, const Validity& best, long map_faces,
                                           ProgressSink& progress) {
  return given.optimize == OptimizeMode::Relocate && !best.valid() && map_faces <= kFullFallbackMaxFaces &&
         given.validity_retries > 0 && !progress.skip_improvements();
}

/// The best attempt so far of retry_until_valid, and every attempt made.
template <class Job>
struct Attempts {
  Job best;
  Validity best_validity;
  std::vector<ValidityAttempt> all;
  int used = 0;
  /// Records `attempt` and keeps `job` (its job) when it is more valid than the best so far. \pre none
  void add(Job&& job, const ValidityAttempt& attempt) {
    all.push_back(attempt);
    if (attempt.validity < best_validity)
      best = std::move(job), best_validity = attempt.validity, used = static_cast<int>(all.size()) - 1;
  }
};

/// A fallback attempt of retry_until_valid: first_attempt(options), recorded and kept when more valid. An InputError
/// (e.g. a density too coarse for that field) leaves the best as it is and says so in a warning naming `what`.
/// \throw as run, but InputError.
template <class Job, class Run, class Judge>
void fall_back(const PipelineOptions& options, int retries, const std::string& what, Run& run, Judge& judge,
               ProgressSink& progress, Attempts<Job>& a) {
  try {
    const SteadyClock::time_point start = SteadyClock::now();
    auto [next, v] = first_attempt(options, retries, run, judge, progress);
    const ValidityAttempt attempt{1.0,
                                  param_job(next).map.edge_length,
                                  v,
                                  param_job(next).options.field_style,
                                  seconds_since(start),
                                  options.optimize,
                                  options.param.features.crisp_crease_degrees > 0};
    a.add(std::move(next), attempt);
  } catch (const InputError& e) {
    param_job(a.best).warnings.push_back(what +
                                         ", tried because this one is not valid, could not be made: " + e.what());
  }
}

/// Attempt 0 = first_attempt(given minus its retries), then FieldStyle::Auto's fallback (fall_back_to_curvature),
/// the long crease chains' (fall_back_to_long_chains) and the full optimization's (fall_back_to_full_optimization),
/// each kept when more valid, then, while the best so far is worth_retrying, up to given.validity_retries further
/// attempts run(attempt_options(given, h0, k)) with the field, features and optimization of the best, keeping the
/// best by `judge`. The kept job's ParamJob (param_job(job)) records the attempts; a warning says when the kept one is
/// not the first or is not valid. A time limit or Ctrl-C ends the retries (recorded as cut short).
/// \throw InputError for invalid options (validate).
template <class Run, class Judge>
auto retry_until_valid(const PipelineOptions& given, Run run, Judge judge, ProgressSink& progress) {
  validate(given);
  PipelineOptions once = given;
  once.validity_retries = 0;
  SteadyClock::time_point start = SteadyClock::now();
  auto [first, first_validity] = first_attempt(once, given.validity_retries, run, judge, progress);
  using Job = decltype(first);
  const FieldStyle first_style = param_job(first).options.field_style;
  Attempts<Job> a{std::move(first), first_validity, {}, 0};
  a.all.push_back({1.0, param_job(a.best).map.edge_length, first_validity, first_style, seconds_since(start),
                   once.optimize, once.param.features.crisp_crease_degrees > 0});
  if (fall_back_to_curvature(given, first_style, a.best_validity, progress)) {
    progress.report("retry", -1, "result not valid: the map made again from the curvature-guided field");
    PipelineOptions curvature = once;
    curvature.field_style = FieldStyle::Curvature;
    fall_back(curvature, given.validity_retries, "the map from the curvature-guided field", run, judge, progress, a);
  }
  if (fall_back_to_long_chains(given, a.best_validity, param_job(a.best).crisp_creases, progress)) {
    progress.report("retry", -1, "result not valid: the map made again following the long crease chains alone");
    PipelineOptions chains = once;
    chains.field_style = param_job(a.best).options.field_style;
    chains.param.features.crisp_crease_degrees = 0;
    fall_back(chains, given.validity_retries, "the map following the long crease chains alone", run, judge, progress,
              a);
  }
  if (fall_back_to_full_optimization(given, a.best_validity, param_job(a.best).map.uv.rows(), progress)) {
    progress.report("retry", -1, "result not valid: the map made again with the full optimization");
    PipelineOptions full = once;
    full.field_style = param_job(a.best).options.field_style;
    full.param.features.crisp_crease_degrees = param_job(a.best).options.param.features.crisp_crease_degrees;
    full.optimize = OptimizeMode::Full;
    fall_back(full, given.validity_retries, "the map with the full optimization", run, judge, progress, a);
  }
  // The density retries keep the field and optimization of the best so far, and its density made finer for a loop
  // (their h is explicit: the job would not say why).
  const LoopDensityRaise raised = param_job(a.best).density.raised;
  PipelineOptions retried = given;
  retried.field_style = param_job(a.best).options.field_style;
  retried.optimize = param_job(a.best).options.optimize;
  retried.param.features.crisp_crease_degrees = param_job(a.best).options.param.features.crisp_crease_degrees;
  const double h0 = param_job(a.best).options.param.density.edge_length;
  for (int k = 1; k <= given.validity_retries && a.best_validity.worth_retrying(); ++k) {
    if (progress.skip_improvements()) {
      record_cut_short(param_job(a.best), "validity retries");
      break;
    }
    progress.report("retry", -1, "result not valid: attempt " + std::to_string(k + 1) + " at a nearby density");
    start = SteadyClock::now();
    Job next = run(attempt_options(retried, h0, k));
    param_job(next).density.raised = raised;
    const Validity v = judge(next);
    const ValidityAttempt attempt{attempt_quads_factor(k, given.param.density),
                                  param_job(next).map.edge_length,
                                  v,
                                  retried.field_style,
                                  seconds_since(start),
                                  retried.optimize,
                                  retried.param.features.crisp_crease_degrees > 0};
    a.add(std::move(next), attempt);
  }
  ParamJob& kept = param_job(a.best);
  kept.field_style_auto = given.field_style == FieldStyle::Auto;
  kept.validity_attempts = a.all;
  kept.validity_attempt_used = a.used;
  kept.options.validity_retries = given.validity_retries;  // the attempts ran without; the job had these
  if (kept.density.raised.loop > 0)
    kept.warnings.insert(kept.warnings.begin(), loop_density_warning(kept.density.raised));
  if (a.used > 0 || !a.best_validity.valid()) kept.warnings.push_back(validity_warning(a.all, a.used));
  return std::move(a.best);
}

}  // namespace quadcover
