// `quadcover info MESH...`: counts, topology and validation problems of mesh files (one file, several, or folders).
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/common.h"
#include "cli/registry.h"
#include "common/errors.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"

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
  const bool manifold = !report.has(ProblemKind::NonManifoldEdge) && !report.has(ProblemKind::NonManifoldVertex);
  const bool orientable = !report.has(ProblemKind::NonOrientable);
  if (report.valid()) {
    const Mesh mesh = build_mesh(soup, vopt).mesh;
    j["vertices"] = mesh.num_vertices();
    j["edges"] = mesh.num_edges();
    j["faces"] = mesh.num_faces();
    j["components"] = mesh.num_components();
    j["boundary_loops"] = mesh.num_boundary_loops();
    j["genus"] = mesh.genus();
    j["euler_characteristic"] = mesh.euler_characteristic();
    j["manifold"] = true;
    j["orientable"] = true;
    j["unreferenced_vertices_dropped"] = report.unreferenced_vertices;
    j["bounding_box_diagonal"] = mesh.bounding_box_diagonal();
    j["mean_edge_length"] = mesh.mean_edge_length();
    j["area"] = mesh.total_area();
  } else {
    j["vertices"] = soup.num_vertices();
    j["faces"] = soup.num_faces();
    if (!report.has(ProblemKind::Empty)) {  // nothing to say about the topology of no faces
      j["manifold"] = manifold;
      j["orientable"] = orientable;
    }
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
                            "euler_characteristic", "manifold", "orientable"})
      if (r.json.contains(key)) std::cout << "  " << key << ": " << r.json[key].dump() << "\n";
  }
  for (const auto& p : r.report.problems) std::cerr << (p.fatal ? "error: " : "warning: ") << p.message << "\n";
  return r.report.valid() ? kOk : kBadInput;
}

void register_info(CLI::App& app, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<InfoOptions>();
  CLI::App* cmd = add_mesh_command(
      app, "info", "Print counts, topology (genus, boundaries, components) and every validation problem of mesh files",
      opt->inputs,
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

const CommandRegistrar registrar{10, "info", register_info};

}  // namespace

}  // namespace quadcover::cli
