#pragma once
// What `param` and `remesh` do alike after their job ran: say every warning of the report on stderr (a degraded
// result is never only in the JSON), write the optional report, plot and HTML page, and return the summary.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/pictures.h"
#include "mesh/mesh.h"
#include "optimize/optimize_field.h"
#include "param/parameterization.h"
#include "quad/quad_mesh.h"

namespace quadcover::cli {

/// The optional outputs of one input (empty = not asked for).
struct JobExtras {
  std::string report, plot, html, png;
};

/// The optional outputs of `param` / `remesh` for one input from --report and the picture options: the paths
/// themselves for one input, in a batch NAME<job_suffix>.json, .html, NAME<png_suffix> and NAME.optimize.png in
/// their folders. \throw as batch_output_path.
JobExtras job_extras(const std::string& input, bool batch, const std::string& report, const PictureCliOptions& pictures,
                     const std::string& job_suffix, const std::string& png_suffix);

/// \throw InputError naming --plot if the plot is asked for without an optimization to plot. \pre none
void check_plot_request(const JobExtras& extras, OptimizeMode mode);

/// Prints "warning: INPUT: sentence" on stderr for each of report["warnings"], also with --quiet. \pre none
void print_warnings(const std::string& input, const nlohmann::json& report);

/// The end of `param` / `remesh` for one input after its main output (`output`) is written: prints the report's
/// warnings, calls write_png(path) when a picture is asked for, writes the extras (write_job_extras, titled
/// "quadcover COMMAND: INPUT") and returns the summary naming `output`. \throw as write_job_extras.
nlohmann::json finish_job(const std::string& command, const std::string& input, const std::string& output,
                          const JobExtras& extras, const Mesh& mesh, const Parameterization& map, const QuadMesh* quads,
                          const nlohmann::json& report, const std::function<void(const std::string&)>& write_png);

/// Writes the JSON report, the Fig. 6.1 plot and the HTML page that `extras` asks for (atomically), the page with the
/// map's checkerboard and, when given, the quad mesh. \throw InputError if the plot has no optimization log.
void write_job_extras(const JobExtras& extras, const std::string& title, const Mesh& mesh, const Parameterization& map,
                      const QuadMesh* quads, const nlohmann::json& report);

}  // namespace quadcover::cli
