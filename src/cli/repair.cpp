// `quadcover repair MESH -o FIXED.obj`: applies the repairs validation can make (consistent orientation, polygons
// fanned into triangles, unreferenced vertices dropped, zero-area triangles that carry no surface removed:
// mesh/degenerate_faces.h) and writes the result; what cannot be repaired (non-manifold, non-orientable, needles,
// ...) is listed with exit 2 and no output, as for every command.
#include <nlohmann/json.hpp>

#include "cli/common.h"
#include "cli/registry.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "mesh/degenerate_faces.h"
#include "mesh/mesh.h"

namespace quadcover::cli {

namespace {

struct RepairOptions : MeshFiles {};

nlohmann::json run_repair(const std::string& input, const std::string& output) {
  const std::string format = mesh_output_format(output);  // a bad output name fails before the work
  PolygonSoup soup = read_mesh(input);
  std::size_t polygons = 0, short_faces = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    polygons += soup.face_size(f) > 3;
    short_faces += soup.face_size(f) < 3;
  }
  if (polygons > 0 && short_faces == 0) soup = triangulate_polygons(soup);
  DegenerateFaceRemoval removed;
  const MeshBuildResult built = build_repaired(std::move(soup), removed);
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
          {"unreferenced_vertices_dropped", built.report.unreferenced_vertices},
          {"repeated_vertex_faces_dropped", removed.repeated_vertex},
          {"duplicate_faces_dropped", removed.duplicates},
          {"zero_area_faces_flipped", removed.flipped_caps},
          {"zero_area_boundary_faces_dropped", removed.boundary_caps},
          {"coincident_corners_merged", removed.merged_needles}};
}

void register_repair(CLI::App* cmd, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<RepairOptions>();
  add_mesh_inputs(*cmd, *opt,
                  "Output mesh .obj/.off/.ply/.stl (one input) or folder (several inputs); default: next to the "
                  "input as NAME.repaired.obj");
  add_global_options(*cmd, global);
  run_on_inputs(*cmd, global, exit_code, opt->inputs,
                {"vertices", "faces", "flipped_faces", "triangulated_polygons", "repeated_vertex_faces_dropped",
                 "duplicate_faces_dropped", "zero_area_faces_flipped", "zero_area_boundary_faces_dropped",
                 "coincident_corners_merged"},
                [opt](const std::string& input, bool batch, ProgressSink&) {
                  return run_repair(input, output_path(input, opt->output, batch, ".repaired.obj"));
                });
}

const CommandRegistrar registrar{
    15, "repair", register_repair,
    "Make a mesh usable where validation can: reorient an orientable but inconsistently oriented surface, "
    "fan-triangulate polygons, drop unreferenced vertices, and remove the zero-area triangles that carry no surface "
    "(a repeated vertex or a repeated face: dropped; a corner on its opposite edge: that edge flipped with the "
    "triangle across it, or dropped on the boundary; two corners at one point: merged; vertex positions never "
    "change); write the triangle mesh (format by extension). Problems it cannot repair (non-manifold, "
    "non-orientable, a merge that would pinch the surface, ...) are listed with exit 2 and nothing is written"};

}  // namespace

}  // namespace quadcover::cli
