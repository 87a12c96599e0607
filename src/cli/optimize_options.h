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
  long max_iterations = kAutoBudget;  ///< E_D evaluations of Algorithm 6.1 (0 = unlimited, -1 = auto)
  bool keep_better = true;            ///< see parameterize_best()
  std::string field = "curvature";    ///< field stage preset (field/compute_frame_field.h, FieldStyle)
  int relaxation = RelaxationOptions{}.iterations;      ///< see param/relaxation.h
  int stiffening = StiffeningOptions{}.max_iterations;  ///< see param/stiffening.h
};

/// The field stage's options of --field (its λ also serves the re-smoothing of --optimize).
FieldOptions field_options(const OptimizeCliOptions& cli);

/// Adds --field, --optimize, --rounding, --max-iterations, --keep-better, --relaxation and --stiffening to `cmd`
/// (validated by CLI11).
void add_optimize_options(CLI::App& cmd, OptimizeCliOptions& options);

/// Library options from the parsed command line (param options are used by --optimize full to measure E_H).
OptimizeOptions to_optimize_options(const OptimizeCliOptions& cli, const ParamOptions& param = {});

/// Sets param.rounding, param.relaxation and param.stiffening from the command line. \throw InputError for an unknown
/// rounding strategy.
void apply_param_options(const OptimizeCliOptions& cli, ParamOptions& param);

/// Runs the optimization on a computed field and returns the field to parameterize; `report` receives the
/// "optimize" object of to_json() (E_D before/after each phase, branch points, log, timings under "seconds").
/// Reports a start and a summary line to `progress` (stage "optimize").
FrameField run_optimize(const Mesh& mesh, const FrameFieldResult& field, const OptimizeCliOptions& cli,
                        const ParamOptions& param, ProgressSink& progress, nlohmann::json& report);

/// parameterize_keep_better() (optimize/optimize_field.h) with the command line's --optimize and --keep-better.
Parameterization parameterize_best(const Mesh& mesh, const FrameField& original, const FrameField& optimized,
                                   const OptimizeCliOptions& cli, const ParamOptions& param, ProgressSink& progress,
                                   nlohmann::json& optimize_report);

/// Thesis Figure 6.1 from an "optimize" report object: E_D and the branch point count over the E_D evaluations
/// of Algorithm 6.1. Written as SVG for a ".svg" path, else PNG (atomically). \throw InputError if the log is
/// empty (--optimize none).
void write_optimization_plot(const std::string& path, const nlohmann::json& optimize_report);

}  // namespace quadcover::cli
