#include "cli/job_output.h"

#include <iostream>
#include <mutex>

#include "cli/common.h"
#include "cli/optimize_options.h"
#include "metrics/param_quality.h"
#include "render/pipeline_pictures.h"

namespace quadcover::cli {

void print_warnings(const std::string& input, const nlohmann::json& report) {
  if (!report.contains("warnings")) return;
  std::lock_guard lock(stderr_mutex());
  for (const auto& w : report["warnings"]) std::cerr << "warning: " << input << ": " << w.get<std::string>() << '\n';
  std::cerr << std::flush;
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

}  // namespace quadcover::cli
