#pragma once
// Command-line options of the low-distortion optimization (thesis Chapter 6) for commands that parameterize
// (param, remesh): --optimize none|relocate|full, --rounding direct|greedy|search1|search2|search3|exact,
// --max-iterations N. The global --time-limit and Ctrl-C stop the optimization early with the best state so far
// (Algorithm 6.1 only ever accepts E_D decreases, so the state at any moment is the best one): the command then
// parameterizes and writes that state.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "common/progress.h"
#include "field/compute_frame_field.h"
#include "optimize/optimize_field.h"
#include "param/parameterization.h"
#include "param/period_rounding.h"

namespace quadcover::cli {

struct OptimizeCliOptions {
  std::string optimize = "relocate";  ///< see optimize/optimize_field.h
  std::string rounding = "search3";   ///< see param/period_rounding.h
  long max_iterations = 3000;         ///< E_D evaluations of Algorithm 6.1 (0 = unlimited)
  bool keep_better = true;            ///< see parameterize_best()
};

/// Adds --optimize, --rounding and --max-iterations to `cmd` (validated by CLI11).
void add_optimize_options(CLI::App& cmd, OptimizeCliOptions& options);

/// Library options from the parsed command line (param options are used by --optimize full to measure E_H).
OptimizeOptions to_optimize_options(const OptimizeCliOptions& cli, const ParamOptions& param = {});

/// Sets param.rounding from --rounding. \throw InputError for an unknown strategy.
void apply_rounding(const OptimizeCliOptions& cli, ParamOptions& param);

/// Runs the optimization on a computed field and returns the field to parameterize; `report` receives the
/// "optimize" object of to_json() (E_D before/after each phase, branch points, log) with the wall-clock values
/// moved under "seconds": {"total", "evaluations_per_second"} (reports keep timings under "seconds" keys).
/// Reports a start and a summary line to `progress` (stage "optimize").
FrameField run_optimize(const Mesh& mesh, const FrameFieldResult& field, const OptimizeCliOptions& cli,
                        const ParamOptions& param, ProgressSink& progress, nlohmann::json& report);

/// The field stage followed by the optimization: compute_frame_field_detailed (ch. 5) then run_optimize (ch. 6).
/// `optimize_report` receives the "optimize" object.
FrameField optimized_field(const Mesh& mesh, const OptimizeCliOptions& cli, const ParamOptions& param,
                           ProgressSink& progress, nlohmann::json& optimize_report);

/// The parameterization of the optimized field; with cli.keep_better (and an optimization that ran) also that of
/// the original field, keeping the one with the lower total distortion E_D + E_H = ½‖X̃ - ∇φ̃‖² (6.1.1): Algorithm
/// 6.1 lowers E_D of the field's own curl energy, which on meshes with boundaries or aligned feature curves does not
/// always lower the map's. Adds "kept" ("optimized" or "original") and both totals to `optimize_report`.
Parameterization parameterize_best(const Mesh& mesh, const FrameField& original, const FrameField& optimized,
                                   const OptimizeCliOptions& cli, const ParamOptions& param, ProgressSink& progress,
                                   nlohmann::json& optimize_report);

/// The report's "rounding" object: strategy asked for and the one that ran, E_H = ½‖H̃_d‖² (6.1.1) of the map and
/// h_sym, and the period matrix's prediction of E_H for direct and for the chosen rounding (6.3), candidates,
/// proven_optimal (exact), stopped_early (--time-limit / Ctrl-C during the search).
nlohmann::json rounding_report(const OptimizeCliOptions& cli, const Parameterization& param);

/// Thesis Figure 6.1 from an "optimize" report object: E_D and the branch point count over the E_D evaluations
/// of Algorithm 6.1. Written as SVG for a ".svg" path, else PNG (atomically). \throw InputError if the log is
/// empty (--optimize none).
void write_optimization_plot(const std::string& path, const nlohmann::json& optimize_report);

}  // namespace quadcover::cli
