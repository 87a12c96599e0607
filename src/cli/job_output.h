#pragma once
// What `param` and `remesh` do alike after their job ran: say every warning of the report on stderr (a degraded
// result is never only in the JSON), write the optional report, plot and HTML page, and return the summary.
#include <nlohmann/json.hpp>
#include <string>

#include "mesh/mesh.h"
#include "param/parameterization.h"
#include "quad/quad_mesh.h"

namespace quadcover::cli {

/// The optional outputs of one input (empty = not asked for).
struct JobExtras {
  std::string report, plot, html;
};

/// Prints "warning: INPUT: sentence" on stderr for each of report["warnings"], also with --quiet. \pre none
void print_warnings(const std::string& input, const nlohmann::json& report);

/// Writes the JSON report, the Fig. 6.1 plot and the HTML page that `extras` asks for (atomically), the page with the
/// map's checkerboard and, when given, the quad mesh. \throw InputError if the plot has no optimization log.
void write_job_extras(const JobExtras& extras, const std::string& title, const Mesh& mesh, const Parameterization& map,
                      const QuadMesh* quads, const nlohmann::json& report);

}  // namespace quadcover::cli
