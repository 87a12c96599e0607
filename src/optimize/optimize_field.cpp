#include "optimize/optimize_field.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "common/errors.h"
#include "common/progress.h"
#include "common/seconds_since.h"
#include "common/side_by_side.h"

namespace quadcover {

OptimizeMode parse_optimize_mode(std::string_view name) {
  if (name == "none") return OptimizeMode::None;
  if (name == "relocate") return OptimizeMode::Relocate;
  if (name == "full") return OptimizeMode::Full;
  throw InputError("", 0, "unknown optimization '" + std::string(name) + "' (expected none, relocate or full)");
}

long auto_evaluation_budget(const Mesh& mesh, OptimizeMode mode) {
  long interior = 0;
  for (int e = 0; e < mesh.num_edges(); ++e) interior += !mesh.is_boundary_edge(e);
  // Calibrated in BENCHMARKS.md ("Algorithm 6.1 and the whole optimized pipeline"). relocate: 3000 (converges within
  // it on the shipped meshes; the e2e baselines were measured with it), fewer above kRelocateFaceEvaluations / 3000
  // faces: an evaluation costs about 0.4-0.5 µs per face on two cores, so that a large mesh of high genus (hundreds
  // of branch points that never converge) spends about a minute, not ten ("Scale-aware relocation budget").
  // Pass 0 to converge.
  constexpr double kRelocateFaceEvaluations = 1e8;
  if (mode == OptimizeMode::Relocate)
    return std::clamp(std::lround(kRelocateFaceEvaluations / std::max(1, mesh.num_faces())), 300L, 3000L);
  // full: one evaluation per 8 interior edges, at least 3000 (20k faces: 3750, below its auto time limit on two
  // cores); large meshes are bounded by auto_time_limit() instead.
  return std::clamp(interior / 8, 3000L, 20000L);
}

double auto_time_limit(const Mesh& mesh, OptimizeMode mode) {
  // full: 2 s + 0.25 ms per face (20k faces: 7 s, 270k: 69 s), so that field + optimize + param stay within the
  // goals of BENCHMARKS.md on two cores; relocate: none (its 3000 evaluations take seconds).
  return mode == OptimizeMode::Full ? 2.0 + 2.5e-4 * mesh.num_faces() : 0.0;
}

const char* to_string(OptimizeMode m) {
  return m == OptimizeMode::None ? "none" : m == OptimizeMode::Relocate ? "relocate" : "full";
}

OptimizeResult optimize_field(const Mesh& mesh, const FrameFieldResult& field, const OptimizeOptions& options,
                              ProgressSink& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  OptimizeResult out;
  out.field = field.field;
  if (options.mode == OptimizeMode::None) return out;
  FrameSmoother smoother(mesh, field.field, field.stability, field.trusted, field.constrained, options.lambda);
  CurlEnergy energy(mesh, smoother, options.energy);
  CurlEstimator screening(energy);  // one for the reduction and the balancing: its far field carries over
  out.setup_seconds = seconds_since(t0);
  CurlReductionOptions ro = curl_reduction_options(options);
  const long budget =
      options.max_evaluations == kAutoBudget ? auto_evaluation_budget(mesh, options.mode) : options.max_evaluations;
  out.max_evaluations = std::max(0L, budget);
  // The time budget: given, or with the auto evaluation budget the auto time limit (full only).
  const double limit = options.time_limit_seconds > 0           ? options.time_limit_seconds
                       : options.max_evaluations == kAutoBudget ? auto_time_limit(mesh, options.mode)
                                                                : 0.0;
  out.time_limit_seconds = limit;
  auto elapsed = [&] { return seconds_since(t0); };
  ro.max_evaluations = out.max_evaluations;
  // full: a third of the evaluation budget is kept for balancing, which also runs when the first reduction used up
  // its share (otherwise a budget-limited run would only create branch points).
  if (options.mode == OptimizeMode::Full && budget > 0) ro.max_evaluations = std::max(1L, budget - budget / 3);
  // full: balancing (with its E_H measurement) gets the last third of the time limit, like the evaluations.
  ro.time_limit_seconds = options.mode == OptimizeMode::Full ? limit * 2 / 3 : limit;
  out.reduction = reduce_curl(mesh, energy, ro, progress, &screening);
  long evaluations = out.reduction.evaluations;
  const bool out_of_time = limit > 0 && elapsed() >= limit;
  if (options.mode == OptimizeMode::Full && !progress.cancelled() && !out_of_time) {
    // 6.4: measure E_H once after curl reduction, Δ_EH = E_H / (2 h_sym), then balance without creation. E_H is
    // fixed by steps 1-5: the map is not finished.
    const SolvedMap p(mesh, energy.field(), options.param, progress);
    out.energy_harmonic_estimate = p.energy_harmonic();
    out.h_sym = p.h_sym();
    // E_H is measured in grid units (the field scaled by p.scale); Δ_ED is in the optimizer's units of the unscaled
    // field, so Δ_EH is brought to those: energies scale with the square of the field.
    out.delta_eh = p.h_sym() > 0 ? p.energy_harmonic() / (2.0 * p.h_sym()) / (p.scale() * p.scale()) : 0;
    if (out.delta_eh > 0) {
      ro.allow_creation = false;
      ro.delta_eh = out.delta_eh;
      if (budget > 0) ro.max_evaluations = std::max(1L, budget - evaluations);
      if (limit > 0) ro.time_limit_seconds = std::max(1e-3, limit - elapsed());
      out.balancing = reduce_curl(mesh, energy, ro, progress, &screening);
      evaluations += out.balancing.evaluations;
    }
  }
  out.field = energy.field();
  out.exact_timings = energy.timings();
  out.estimate_timings = screening.timings();
  out.seconds = seconds_since(t0);
  out.evaluations_per_second = out.seconds > 0 ? evaluations / out.seconds : 0;
  return out;
}

CurlReductionOptions curl_reduction_options(const OptimizeOptions& options) {
  CurlReductionOptions ro;
  ro.allow_creation = options.mode == OptimizeMode::Full;
  ro.cancellation_neighbours = options.cancellation_neighbours;
  ro.max_evaluations = options.max_evaluations;
  ro.time_limit_seconds = options.time_limit_seconds;
  ro.local_estimates = options.local_estimates;
  ro.threads = options.threads;
  return ro;
}

nlohmann::json to_json(const OptimizeResult& r, OptimizeMode mode) {
  nlohmann::json j;
  j["mode"] = to_string(mode);
  const bool balanced = !r.balancing.log.empty();
  const CurlReductionResult& last = balanced ? r.balancing : r.reduction;
  j["E_D_before"] = r.reduction.initial_energy;
  j["E_D_after_reduction"] = r.reduction.final_energy;
  j["E_D_after"] = mode == OptimizeMode::None ? r.reduction.initial_energy : last.final_energy;
  j["branch_points_before"] = r.reduction.initial_branch_points;
  j["branch_points_after"] = last.final_branch_points;
  j["evaluations"] = r.reduction.evaluations + r.balancing.evaluations;
  j["accepted"] = r.reduction.accepted + r.balancing.accepted;
  j["exact_evaluations"] = r.reduction.exact_evaluations + r.balancing.exact_evaluations;
  j["cancelled_pairs"] = r.balancing.cancelled_pairs;
  j["E_H_estimate"] = r.energy_harmonic_estimate;
  j["h_sym"] = r.h_sym;
  j["delta_EH"] = r.delta_eh;
  const CurlEnergyTimings &x = r.exact_timings, &s = r.estimate_timings;
  j["seconds"] = {{"total", r.seconds},
                  {"setup", r.setup_seconds},
                  {"evaluations_per_second", r.evaluations_per_second},
                  {"exact",
                   {{"smoothing", x.smoothing},
                    {"curl", x.curl},
                    {"update", x.update},
                    {"solve", x.solve},
                    {"commit", x.commit},
                    {"prepare_estimates", x.prepare},
                    {"back_solve", x.shares}}},
                  {"estimates",
                   {{"smoothing", s.smoothing},
                    {"curl", s.curl},
                    {"update", s.update},
                    {"solve", s.solve},
                    {"count", s.evaluations}}}};
  j["max_evaluations"] = r.max_evaluations;
  j["time_limit_seconds"] = r.time_limit_seconds;
  j["stopped_early"] = r.reduction.stopped_early || r.balancing.stopped_early;
  // The first reduction's stop decides unless balancing ran (it then starts from the reduction's state).
  const std::string& by =
      r.reduction.stopped_early || r.balancing.log.empty() ? r.reduction.stopped_by : r.balancing.stopped_by;
  j["stopped_by"] = mode == OptimizeMode::None ? "converged" : by;
  j["converged"] = !(r.reduction.stopped_early || r.balancing.stopped_early);
  nlohmann::json log = nlohmann::json::array();
  for (const auto* part : {&r.reduction, &r.balancing})
    for (const auto& e : part->log)
      log.push_back({{"phase", e.phase},
                     {"evaluation", e.evaluation},
                     {"E_D", e.energy},
                     {"branch_points", e.branch_points},
                     {"accepted", e.accepted}});
  j["log"] = std::move(log);
  return j;
}

namespace {

double energy_curl_plus_harmonic(const SolvedMap& s) { return s.energy_curl() + s.energy_harmonic(); }

/// Records the comparison in `report`; true if the original field's map wins (strictly lower E_D + E_H).
bool original_wins(double total_original, double total_optimized, ProgressSink& progress, nlohmann::json& report) {
  report["E_D_plus_E_H_optimized"] = total_optimized;
  report["E_D_plus_E_H_original"] = total_original;
  if (total_original >= total_optimized) return false;
  report["kept"] = "original";
  progress.report("optimize", 1,
                  "kept the original field: E_D + E_H " + std::to_string(total_original) + " < " +
                      std::to_string(total_optimized) + " of the optimized one");
  return true;
}

/// Both maps solved at once, one per core (common/side_by_side.h), and the kept one finished.
Parameterization keep_better_side_by_side(const Mesh& mesh, const FrameField& original, const FrameField& optimized,
                                          const ParamOptions& param, ProgressSink& progress, nlohmann::json& report) {
  SerializedProgress shared(progress);
  std::optional<SolvedMap> from_original, from_optimized;
  run_side_by_side(
      mesh.num_faces(), [&] { from_original.emplace(mesh, original, param, shared); },
      [&] { from_optimized.emplace(mesh, optimized, param, shared); });
  if (original_wins(energy_curl_plus_harmonic(*from_original), energy_curl_plus_harmonic(*from_optimized), progress,
                    report)) {
    from_optimized.reset();
    return std::move(*from_original).finish();
  }
  from_original.reset();
  return std::move(*from_optimized).finish();
}

}  // namespace

Parameterization parameterize_keep_better(const Mesh& mesh, const FrameField& original, const FrameField& optimized,
                                          const ParamOptions& param, OptimizeMode mode, bool keep_better,
                                          ProgressSink& progress, nlohmann::json& report) {
  if (mode == OptimizeMode::None) return parameterize(mesh, optimized, param, progress);
  report["kept"] = "optimized";
  if (!keep_better || progress.skip_improvements()) return parameterize(mesh, optimized, param, progress);
  progress.report("optimize", -1, "parameterizing the original field for comparison (keep better)");
  if (side_by_side(mesh.num_faces()))
    return keep_better_side_by_side(mesh, original, optimized, param, progress, report);
  // E_D + E_H are fixed by steps 1-5 (param/parameterize.h SolvedMap): only the kept map is finished, and the
  // original one, solved first and dropped, is solved again only if it wins (two solves are never held at once).
  const double total_original = energy_curl_plus_harmonic(SolvedMap(mesh, original, param, progress));
  {
    SolvedMap solved(mesh, optimized, param, progress);
    if (!original_wins(total_original, energy_curl_plus_harmonic(solved), progress, report))
      return std::move(solved).finish();
  }
  return parameterize(mesh, original, param, progress);
}

}  // namespace quadcover
