#pragma once
// One call for the CLI and Python: low-distortion optimization of a frame field's matching (thesis Chapter 6).
//   none      the field is returned unchanged;
//   relocate  Algorithm 6.1 without creation of branch points (cancellation + sorted curl reduction: branch points
//             only move or cancel, Figures 6.7c / 6.8c);
//   full      Algorithm 6.1 with creation, then balancing (6.4): E_H and h_sym are measured by one parameterization
//             of the reduced field, Δ_EH = E_H / (2 h_sym), and pairs are cancelled while Δ_ED < Δ_EH.
#include <nlohmann/json.hpp>
#include <string_view>

#include "common/progress.h"
#include "field/compute_frame_field.h"
#include "optimize/curl_reduction.h"
#include "param/parameterize.h"

namespace quadcover {

enum class OptimizeMode { None, Relocate, Full };
/// OptimizeOptions::max_evaluations: derive the budget from the mesh (auto_evaluation_budget).
inline constexpr long kAutoBudget = -1;
/// Parses "none|relocate|full". \throw InputError otherwise.
OptimizeMode parse_optimize_mode(std::string_view name);
/// "none", "relocate" or "full". \pre none
const char* to_string(OptimizeMode mode);

struct OptimizeOptions {
  OptimizeMode mode = OptimizeMode::Relocate;
  /// λ of the re-smoothing E(α) (5.3) after each matching change; the field stage's default.
  double lambda = FieldOptions{}.lambda;
  int cancellation_neighbours = 3;  ///< k of Algorithm 6.1
  /// Budget: E_D evaluations (screened candidates; 0 = unlimited, kAutoBudget = auto_evaluation_budget()) and
  /// seconds (0 = none; with the auto evaluation budget, `full` also gets auto_time_limit()); the best state so far
  /// is returned. `full` gives the first reduction two thirds of the evaluations and of the time and balancing the
  /// rest. The report says whether a run converged or what stopped it. A time limit that binds makes the result
  /// depend on the machine's speed: `relocate` and explicit evaluation budgets have none by default.
  long max_evaluations = kAutoBudget;
  double time_limit_seconds = 0;
  CurlEnergyOptions energy;
  /// Screen candidates with local E_D estimates (CurlReductionOptions::local_estimates) on `threads` threads
  /// (0 = all cores; the result does not depend on it).
  bool local_estimates = true;
  int threads = 0;
  ParamOptions param;  ///< used by `full` to measure E_H for Δ_EH
};

struct OptimizeResult {
  FrameField field;                     ///< optimized cross field with its matching
  CurlReductionResult reduction;        ///< first curl reduction (with creation for `full`)
  CurlReductionResult balancing;        ///< `full` only: the balancing run (creation disallowed)
  double energy_harmonic_estimate = 0;  ///< `full`: E_H measured after the first reduction
  int h_sym = 0;                        ///< `full`: h_sym of that parameterization
  double delta_eh = 0;                  ///< `full`: Δ_EH = E_H / (2 h_sym), in the unscaled field's units (÷ scale²)
  double evaluations_per_second = 0;
  double seconds = 0;
  double setup_seconds = 0;            ///< smoother, 𝔏̄* factorization and E_D before the first evaluation
  long max_evaluations = 0;            ///< the budget used (auto resolved; 0 = unlimited)
  double time_limit_seconds = 0;       ///< the time limit used (auto resolved; 0 = none)
  CurlEnergyTimings exact_timings;     ///< exact evaluations, commits, CurlEstimator::prepare, shares (wall seconds)
  CurlEnergyTimings estimate_timings;  ///< screening estimates, summed over the threads
};

/// The CurlReductionOptions of `options` as given (creation with mode full; budget and time limit unresolved). \pre none
CurlReductionOptions curl_reduction_options(const OptimizeOptions& options);

/// The default evaluation budget (deterministic, no clock): `relocate` 3000 up to 33k faces (enough to converge on
/// the test meshes), then 1e8 / #faces, at least 300 (each evaluation costs time in proportion to the faces);
/// `full` grows with the number of interior edges, capped, to stay within the whole-pipeline goals of
/// BENCHMARKS.md (20k faces < 10 s, 270k < 5 min on two cores). \pre none
long auto_evaluation_budget(const Mesh& mesh, OptimizeMode mode);
/// The default time limit in seconds with the auto budget: `full` 2 s + 0.25 ms per face, `relocate` none (0).
/// \pre none
double auto_time_limit(const Mesh& mesh, OptimizeMode mode);

/// \pre field came from compute_frame_field_detailed on `mesh`.
/// \throw NumericalError if a factorization fails.
OptimizeResult optimize_field(const Mesh& mesh, const FrameFieldResult& field, const OptimizeOptions& options = {},
                              ProgressSink& progress = null_progress());

/// Report keys: mode, E_D_before, E_D_after, branch_points_before/after, evaluations, max_evaluations,
/// time_limit_seconds, exact_evaluations, accepted, cancelled_pairs, stopped_early, converged, stopped_by ("converged",
/// "evaluations", "time", "cancelled"), delta_EH, h_sym, log (phase, evaluation, E_D, branch_points), and the
/// wall-clock values under "seconds": {total, evaluations_per_second, exact, estimates} (reports keep timings under
/// "seconds" keys, so that everything else is byte-identical between runs). \pre none
nlohmann::json to_json(const OptimizeResult& result, OptimizeMode mode);

/// parameterize() of the optimized field; when `mode` optimized and `keep_better` is set, also of the original
/// field, keeping the map with the lower total distortion E_D + E_H = ½‖X̃ − ∇φ̃‖² (6.1.1): Algorithm 6.1 lowers
/// the field's E_D, which need not lower the map's. Adds "kept" ("optimized" or "original") and, when compared,
/// both totals to `report`. Only the kept map is finished (param/parameterize.h SolvedMap); the two are solved side
/// by side on small meshes (common/side_by_side.h), one after the other on large ones. \pre original and
/// optimized belong to mesh. \throw as parameterize().
Parameterization parameterize_keep_better(const Mesh& mesh, const FrameField& original, const FrameField& optimized,
                                          const ParamOptions& param, OptimizeMode mode, bool keep_better,
                                          ProgressSink& progress, nlohmann::json& report);

}  // namespace quadcover
