#include "cli/optimize_options.h"

namespace quadcover::cli {

void add_optimize_options(CLI::App& cmd, OptimizeCliOptions& options) {
  cmd.add_option("--optimize", options.optimize,
                 "Distortion optimization (thesis ch. 6): none; relocate = Algorithm 6.1 moving/cancelling branch "
                 "points only; full = with creation of branch points and balancing (6.4)")
      ->check(CLI::IsMember({"none", "relocate", "full"}))
      ->capture_default_str();
  cmd.add_option("--rounding", options.rounding,
                 "Period rounding (6.3): direct, greedy (MIQ), search1/2/3 (change up to r periods at a time), "
                 "exact (closest vector, small instances)")
      ->check(CLI::IsMember({"direct", "greedy", "search1", "search2", "search3", "exact"}))
      ->capture_default_str();
  cmd.add_option("--max-iterations", options.max_iterations,
                 "Budget of E_D evaluations for --optimize (0 = until converged)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
}

OptimizeOptions to_optimize_options(const OptimizeCliOptions& cli, const ParamOptions& param) {
  OptimizeOptions o;
  o.mode = parse_optimize_mode(cli.optimize);
  o.max_evaluations = cli.max_iterations;
  o.param = param;
  return o;
}

FrameField run_optimize(const Mesh& mesh, const FrameFieldResult& field, const OptimizeCliOptions& cli,
                        const ParamOptions& param, ProgressSink& progress, nlohmann::json& report) {
  const OptimizeOptions o = to_optimize_options(cli, param);
  OptimizeResult r = optimize_field(mesh, field, o, progress);
  report = to_json(r, o.mode);
  report["rounding"] = cli.rounding;
  return std::move(r.field);
}

}  // namespace quadcover::cli
