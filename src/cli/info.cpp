// `quadcover info MESH`: counts, topology and validation problems of a mesh file.
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/registry.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"

namespace quadcover::cli {

namespace {

struct InfoOptions {
  std::string input;
  bool triangulate = false;
  bool fix_orientation = false;
};

int run_info(const InfoOptions& opt, const GlobalOptions& global) {
  const PolygonSoup soup = read_mesh(opt.input);
  ValidationOptions vopt;
  vopt.triangulate = opt.triangulate;
  vopt.fix_orientation = opt.fix_orientation;
  const ValidationReport report = validate(soup, vopt);
  nlohmann::json j;
  j["file"] = opt.input;
  j["valid"] = report.valid();
  nlohmann::json problems = nlohmann::json::array();
  for (const auto& p : report.problems)
    problems.push_back({{"kind", to_string(p.kind)}, {"fatal", p.fatal}, {"message", p.message},
                        {"faces", p.faces}, {"vertices", p.vertices}});
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
    j["manifold"] = manifold;
    j["orientable"] = orientable;
  }
  if (global.json) {
    std::cout << j.dump(2) << "\n";
  } else if (!global.quiet) {
    std::cout << opt.input << "\n";
    for (const char* key : {"vertices", "edges", "faces", "components", "boundary_loops", "genus",
                            "euler_characteristic", "manifold", "orientable"})
      if (j.contains(key)) std::cout << "  " << key << ": " << j[key].dump() << "\n";
  }
  for (const auto& p : report.problems)
    std::cerr << (p.fatal ? "error: " : "warning: ") << p.message << "\n";
  return report.valid() ? kOk : kBadInput;
}

}  // namespace

namespace {
void register_info(CLI::App& app, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand("info", "Print counts, topology (genus, boundaries, components) and every validation problem of a mesh");
  cmd->add_option("mesh", opt->input, "Input mesh (.obj, .off, .ply, .stl)")->required()->check(CLI::ExistingFile);
  cmd->add_flag("--triangulate", opt->triangulate, "Fan-triangulate polygons instead of reporting them as errors");
  cmd->add_flag("--fix-orientation", opt->fix_orientation, "Reorient an orientable but inconsistently oriented mesh");
  cmd->add_flag("--json", global.json, "Print the result as JSON on stdout");
  cmd->add_flag("-q,--quiet", global.quiet, "Print nothing but errors");
  cmd->callback([opt, &global, &exit_code] { exit_code = run_info(*opt, global); });
}

const CommandRegistrar registrar{10, "info", register_info};
}  // namespace

}  // namespace quadcover::cli
