#pragma once
// Command-line options of the low-distortion optimization (thesis Chapter 6) for commands that parameterize
// (param, remesh): --optimize none|relocate|full, --rounding direct|greedy|search1|search2|search3|exact,
// --max-iterations N. The global --time-limit stops the optimization early with the best state so far.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "common/progress.h"
#include "field/compute_frame_field.h"
#include "optimize/optimize_field.h"
#include "param/period_rounding.h"

namespace quadcover::cli {

struct OptimizeCliOptions {
  std::string optimize = "relocate";  ///< see optimize/optimize_field.h
  std::string rounding = "search3";   ///< see param/period_rounding.h
  long max_iterations = 3000;         ///< E_D evaluations of Algorithm 6.1 (0 = unlimited)
};

/// Adds --optimize, --rounding and --max-iterations to `cmd` (validated by CLI11).
void add_optimize_options(CLI::App& cmd, OptimizeCliOptions& options);

/// Library options from the parsed command line (param options are used by --optimize full to measure E_H).
OptimizeOptions to_optimize_options(const OptimizeCliOptions& cli, const ParamOptions& param = {});

/// Runs the optimization on a computed field and returns the field to parameterize; `report` receives the
/// "optimize" object of to_json() (E_D before/after each phase, branch points, evaluations per second, log).
FrameField run_optimize(const Mesh& mesh, const FrameFieldResult& field, const OptimizeCliOptions& cli,
                        const ParamOptions& param, ProgressSink& progress, nlohmann::json& report);

}  // namespace quadcover::cli
