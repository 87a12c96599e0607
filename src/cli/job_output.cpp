#include "cli/job_output.h"

#include <iostream>
#include <mutex>

#include "cli/common.h"
#include "cli/optimize_options.h"
#include "common/errors.h"
#include "metrics/param_quality.h"
#include "pipeline/job_report.h"
#include "render/pipeline_pictures.h"

namespace quadcover::cli {

void print_warnings(const std::string& input, const nlohmann::json& report) {
  if (!report.contains("warnings")) return;
  std::lock_guard lock(stderr_mutex());
  for (const auto& w : report["warnings"]) std::cerr << "warning: " << input << ": " << w.get<std::string>() << '\n';
  std::cerr << std::flush;
}

JobExtras job_extras(const std::string& input, bool batch, const std::string& report, const PictureCliOptions& pictures,
                     const std::string& job_suffix, const std::string& png_suffix) {
  auto path = [&](const std::string& o, const std::string& suffix) {
    return optional_output_path(input, o, batch, suffix);
  };
  JobExtras extras;  // in the order the commands always named them
  extras.report = path(report, job_suffix + ".json");
  extras.png = path(pictures.png, png_suffix);
  extras.html = path(pictures.report_html, job_suffix + ".html");
  extras.plot = path(pictures.plot, ".optimize.png");
  return extras;
}

void check_plot_request(const JobExtras& extras, OptimizeMode mode) {
  if (!extras.plot.empty() && mode == OptimizeMode::None)
    throw InputError("--plot", 0, "the optimization plot needs --optimize relocate or full");
}

void write_job_extras(const JobExtras& extras, const std::string& title, const Mesh& mesh, const Parameterization& map,
                      const QuadMesh* quads, const nlohmann::json& report) {
  if (!extras.report.empty()) write_json_atomically(extras.report, report);
  if (!extras.plot.empty()) write_optimization_plot(extras.plot, report["optimize"]);
  if (!extras.html.empty()) {
    const ParamQuality quality = param_quality(mesh, map);
    write_pipeline_report(extras.html, title, mesh, &map, quads, report, &quality);
  }
}

nlohmann::json finish_job(const std::string& command, const std::string& input, const std::string& output,
                          const JobExtras& extras, const Mesh& mesh, const Parameterization& map, const QuadMesh* quads,
                          const nlohmann::json& report, const std::function<void(const std::string&)>& write_png) {
  print_warnings(input, report);
  if (!extras.png.empty()) write_png(extras.png);
  write_job_extras(extras, "quadcover " + command + ": " + input, mesh, map, quads, report);
  nlohmann::json summary = report_summary(report);
  summary["output"] = output;
  return summary;
}

}  // namespace quadcover::cli
