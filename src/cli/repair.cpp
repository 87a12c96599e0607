// `quadcover repair MESH -o FIXED.obj`: applies the repairs validation can make (consistent orientation, polygons
// fanned into triangles, unreferenced vertices dropped) and writes the result; what cannot be repaired (non-manifold,
// non-orientable, degenerate, ...) is listed with exit 2 and no output, as for every command.
#include <nlohmann/json.hpp>

#include "cli/common.h"
#include "cli/registry.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "mesh/mesh.h"

namespace quadcover::cli {

namespace {

struct RepairOptions : MeshFiles {};

nlohmann::json run_repair(const std::string& input, const std::string& output) {
  const std::string format = mesh_output_format(output);  // a bad output name fails before the work
  const PolygonSoup soup = read_mesh(input);
  std::size_t polygons = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) polygons += soup.face_size(f) > 3;
  ValidationOptions options;
  options.triangulate = true;
  options.fix_orientation = true;
  const MeshBuildResult built = build_mesh(soup, options);
  const Mesh& mesh = built.mesh;
  std::vector<std::vector<int>> faces(static_cast<std::size_t>(mesh.num_faces()));
  for (int f = 0; f < mesh.num_faces(); ++f)
    faces[static_cast<std::size_t>(f)] = {mesh.F()(f, 0), mesh.F()(f, 1), mesh.F()(f, 2)};
  write_polygon_mesh(output, mesh.V(), faces);
  return {{"output", output},
          {"format", format},
          {"vertices", mesh.num_vertices()},
          {"faces", mesh.num_faces()},
          {"flipped_faces", built.report.flipped_faces},
          {"triangulated_polygons", polygons},
          {"unreferenced_vertices_dropped", built.report.unreferenced_vertices}};
}

void register_repair(CLI::App* cmd, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<RepairOptions>();
  add_mesh_inputs(*cmd, *opt,
                  "Output mesh .obj/.off/.ply/.stl (one input) or folder (several inputs); default: next to the "
                  "input as NAME.repaired.obj");
  add_global_options(*cmd, global);
  run_on_inputs(*cmd, global, exit_code, opt->inputs, {"vertices", "faces", "flipped_faces", "triangulated_polygons"},
                [opt](const std::string& input, bool batch, ProgressSink&) {
                  return run_repair(input, output_path(input, opt->output, batch, ".repaired.obj"));
                });
}

const CommandRegistrar registrar{
    15, "repair", register_repair,
    "Make a mesh usable where validation can: reorient an orientable but inconsistently oriented surface, "
    "fan-triangulate polygons and drop unreferenced vertices; write the triangle mesh (format by extension). "
    "Problems it cannot repair are listed with exit 2 and nothing is written"};

}  // namespace

}  // namespace quadcover::cli
