// `quadcover info MESH...`: counts, topology and validation problems of mesh files (one file, several, or folders).
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/common.h"
#include "cli/registry.h"
#include "common/errors.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"
#include "mesh/surface_counts.h"

namespace quadcover::cli {

namespace {

struct InfoOptions {
  std::vector<std::string> inputs;
  bool triangulate = false;
  bool fix_orientation = false;
};

struct InfoResult {
  nlohmann::json json;
  ValidationReport report;
};

InfoResult inspect(const std::string& input, const InfoOptions& opt) {
  const PolygonSoup soup = read_mesh(input);
  ValidationOptions vopt;
  vopt.triangulate = opt.triangulate;
  vopt.fix_orientation = opt.fix_orientation;
  InfoResult r;
  r.report = validate(soup, vopt);
  const ValidationReport& report = r.report;
  nlohmann::json& j = r.json;
  j["file"] = input;
  j["valid"] = report.valid();
  nlohmann::json problems = nlohmann::json::array();
  for (const auto& p : report.problems)
    problems.push_back({{"kind", to_string(p.kind)},
                        {"fatal", p.fatal},
                        {"message", p.message},
                        {"faces", p.faces},
                        {"vertices", p.vertices}});
  j["problems"] = problems;
  // Topology from mesh/surface_counts.h, the definition `metrics` and the reports use, for any mesh whose indices
  // are in range (valid or not, triangles or polygons): the mesh as built when valid, else the file's faces.
  bool triangles = true;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) triangles = triangles && soup.face_size(f) == 3;
  j["vertices"] = soup.num_vertices();
  j["faces"] = soup.num_faces();
  std::optional<SurfaceCounts> counts;
  if (report.valid()) {
    const Mesh mesh = build_mesh(soup, vopt).mesh;
    counts = surface_counts(mesh);
    counts->isolated_vertices = static_cast<int>(report.unreferenced_vertices);  // dropped by the build
    j["bounding_box_diagonal"] = mesh.bounding_box_diagonal();
    j["mean_edge_length"] = mesh.mean_edge_length();
    j["area"] = mesh.total_area();
    j["unreferenced_vertices_dropped"] = report.unreferenced_vertices;
  } else if (!report.has(ProblemKind::Empty) && !report.has(ProblemKind::IndexOutOfRange)) {
    counts = surface_counts(static_cast<int>(soup.num_vertices()),
                            soup_polygons(opt.triangulate ? triangulate_polygons(soup) : soup));
  }
  if (counts) {
    const nlohmann::json topology = to_json(*counts);
    for (const auto& [key, value] : topology.items()) j[key] = value;
    // Orientability needs the validation's search (triangles only); a consistently oriented mesh is orientable.
    if (counts->oriented())
      j["orientable"] = true;
    else if (triangles || opt.triangulate)
      j["orientable"] = !report.has(ProblemKind::NonOrientable);
    else
      j["orientable"] = nullptr;
  }
  return r;
}

int run_single(const std::string& input, const InfoOptions& opt, const GlobalOptions& global) {
  const InfoResult r = inspect(input, opt);
  if (global.json) {
    std::cout << r.json.dump(2) << "\n";
  } else if (!global.quiet) {
    std::cout << input << "\n";
    for (const char* key : {"vertices", "edges", "faces", "components", "boundary_loops", "genus",
                            "euler_characteristic", "manifold", "oriented", "orientable", "non_quads"})
      if (r.json.contains(key)) std::cout << "  " << key << ": " << r.json[key].dump() << "\n";
  }
  for (const auto& p : r.report.problems) std::cerr << (p.fatal ? "error: " : "warning: ") << p.message << "\n";
  return r.report.valid() ? kOk : kBadInput;
}

void register_info(CLI::App* cmd, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<InfoOptions>();
  add_input_option(
      *cmd, opt->inputs,
      "Input meshes (.obj, .off, .ply, .stl) or folders of them; several are checked in parallel and summarized in "
      "a table");
  cmd->add_flag("--triangulate", opt->triangulate,
                "Check the mesh as if its polygons were fan-triangulated (`quadcover repair` writes that mesh)");
  cmd->add_flag("--fix-orientation", opt->fix_orientation,
                "Check the mesh as if it were consistently reoriented (`quadcover repair` writes that mesh)");
  add_global_options(*cmd, global);
  cmd->callback([opt, &global, &exit_code] {
    if (!is_batch(opt->inputs)) {
      set_standard_stream_format(global.format);
      exit_code = run_single(opt->inputs[0], *opt, global);
      return;
    }
    BatchSpec spec;
    spec.inputs = opt->inputs;
    spec.summary_columns = {"vertices", "faces", "components", "boundary_loops", "genus"};
    exit_code = run_batch(spec, global, [opt](const std::string& input, ProgressSink&) {
      InfoResult r = inspect(input, *opt);
      if (!r.report.valid()) {
        std::vector<std::string> problems;
        for (const auto& p : r.report.problems)
          if (p.fatal) problems.push_back(p.message);
        const std::string what = input + ": not a valid mesh (" + std::to_string(problems.size()) + " problems)";
        throw TopologyError(what, std::move(problems));
      }
      return r.json;
    });
  });
}

const CommandRegistrar registrar{
    10, "info", register_info,
    "Print counts, topology (genus, boundaries, components) and every validation problem of mesh files"};

}  // namespace

}  // namespace quadcover::cli
