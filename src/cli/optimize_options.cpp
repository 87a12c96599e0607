#include "cli/optimize_options.h"

#include <cstdio>
#include <limits>
#include <string>

#include "cli/commands.h"
#include "common/errors.h"
#include "render/html_report.h"
#include "render/plots.h"

namespace quadcover::cli {

void add_optimize_options(CLI::App& cmd, OptimizeCliOptions& options) {
  cmd.add_option("--field", options.field,
                 "Guiding cross field: curvature = aligned to the principal curvature directions where they are "
                 "reliable (thesis ch. 5); smooth = the smoothest cross field with a weak pull to them (as MIQ), "
                 "lower distortion on organic shapes (Table 7.1 in BENCHMARKS.md). Features are followed by both")
      ->check(CLI::IsMember({"curvature", "smooth"}))
      ->capture_default_str();
  cmd.add_option("--optimize", options.optimize,
                 "Distortion optimization of the field's matching (thesis ch. 6) before parameterizing: none; "
                 "relocate = Algorithm 6.1 moving and cancelling branch points, never creating any; full = with "
                 "creation of branch points, then balancing (6.4) when the budget allows. Default relocate: on the "
                 "Table 7.1 bunny (BENCHMARKS.md) it lowers E_D and the branch point count in 0.3 s and keeps the "
                 "quad mesh closed and all-quad with the fewest irregular vertices; full lowers RSD and ARAP "
                 "further but adds branch points, irregular vertices and non-quads and takes 5-50x longer")
      ->check(CLI::IsMember({"none", "relocate", "full"}))
      ->capture_default_str();
  cmd.add_option("--rounding", options.rounding,
                 "Period rounding (6.3) minimizing E_H with the period matrix: direct (nearest lattice point, no "
                 "matrix), greedy (MIQ), search1/2/3 (change up to r periods at a time; the thesis's r = 3), "
                 "exact (closest vector by LLL + enumeration, up to 48 periods, else search3)")
      ->check(CLI::IsMember({"direct", "greedy", "search1", "search2", "search3", "exact"}))
      ->capture_default_str();
  cmd.add_option("--max-iterations", options.max_iterations,
                 "Budget of E_D evaluations for --optimize: -1 = auto (relocate 3000; full one per 8 interior "
                 "edges, 3000 to 20000, and at most 2 s + 0.25 ms per face, so that the whole pipeline stays "
                 "within the goal times of BENCHMARKS.md), 0 = until converged; "
                 "--time-limit and Ctrl-C also stop it, keeping the best field so far. The report's "
                 "optimize.stopped_by says whether it converged or what stopped it")
      ->check(CLI::Range(-1L, std::numeric_limits<long>::max()))
      ->capture_default_str();
  cmd.add_option("--keep-better", options.keep_better,
                 "Also parameterize the original field and keep whichever map has the lower E_D + E_H (6.1.1); "
                 "reported as optimize.kept. One extra parameterization; false always uses the optimized field")
      ->capture_default_str();
  cmd.add_option("--relaxation", options.relaxation, kRelaxationHelp)
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd.add_option("--stiffening", options.stiffening, kStiffeningHelp)
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
}

FieldOptions field_options(const OptimizeCliOptions& cli) { return field_options(parse_field_style(cli.field)); }

OptimizeOptions to_optimize_options(const OptimizeCliOptions& cli, const ParamOptions& param) {
  OptimizeOptions o;
  o.mode = parse_optimize_mode(cli.optimize);
  o.lambda = field_options(cli).lambda;
  o.max_evaluations = cli.max_iterations;
  o.param = param;
  return o;
}

void apply_param_options(const OptimizeCliOptions& cli, ParamOptions& param) {
  try {
    param.rounding.strategy = parse_rounding_strategy(cli.rounding);
  } catch (const InputError& e) {
    throw InputError("--rounding", 0, e.what());
  }
  param.relaxation.iterations = cli.relaxation;
  param.stiffening.max_iterations = cli.stiffening;
}

FrameField run_optimize(const Mesh& mesh, const FrameFieldResult& field, const OptimizeCliOptions& cli,
                        const ParamOptions& param, ProgressSink& progress, nlohmann::json& report) {
  const OptimizeOptions o = to_optimize_options(cli, param);
  if (o.mode != OptimizeMode::None) progress.report("optimize", 0, "Algorithm 6.1 (" + cli.optimize + ")");
  OptimizeResult r = optimize_field(mesh, field, o, progress);
  report = to_json(r, o.mode);
  report["rounding"] = cli.rounding;
  if (o.mode != OptimizeMode::None) {
    char line[200];
    const std::string by = report["stopped_by"].get<std::string>();
    std::snprintf(line, sizeof line, "E_D %.4g -> %.4g, branch points %d -> %d, %ld evaluations (%.0f/s), %s",
                  report["E_D_before"].get<double>(), report["E_D_after"].get<double>(),
                  report["branch_points_before"].get<int>(), report["branch_points_after"].get<int>(),
                  report["evaluations"].get<long>(), r.evaluations_per_second,
                  by == "converged"     ? "converged"
                  : by == "evaluations" ? ("stopped on the budget of " + std::to_string(r.max_evaluations)).c_str()
                                        : ("stopped early (" + by + ")").c_str());
    progress.report("optimize", 1, line);
  }
  return std::move(r.field);
}

Parameterization parameterize_best(const Mesh& mesh, const FrameField& original, const FrameField& optimized,
                                   const OptimizeCliOptions& cli, const ParamOptions& param, ProgressSink& progress,
                                   nlohmann::json& optimize_report) {
  return parameterize_keep_better(mesh, original, optimized, param, parse_optimize_mode(cli.optimize), cli.keep_better,
                                  progress, optimize_report);
}

void write_optimization_plot(const std::string& path, const nlohmann::json& optimize_report) {
  const nlohmann::json& log = optimize_report.contains("log") ? optimize_report["log"] : nlohmann::json::array();
  if (!log.is_array() || log.empty())
    throw InputError("--plot", 0, "no optimization log to plot (use --optimize relocate or full)");
  write_line_plot(path, optimization_history_plot(log));
}

}  // namespace quadcover::cli
