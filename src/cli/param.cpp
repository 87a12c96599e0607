// `quadcover param MESH -o OUT.obj`: the seamless QuadCover parameterization (thesis Chapters 2-4) guided by the
// curvature frame field of Chapter 5, written as an OBJ with per-corner texture coordinates in grid units.
#include <nlohmann/json.hpp>

#include "cli/common.h"
#include "cli/job_output.h"
#include "cli/optimize_options.h"
#include "cli/pictures.h"
#include "cli/registry.h"
#include "common/errors.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "io/write_ply.h"
#include "mesh/mesh.h"
#include "pipeline/job_report.h"
#include "pipeline/parameterize_mesh.h"
#include "render/pipeline_pictures.h"

namespace quadcover::cli {

namespace {

struct ParamCmdOptions : MeshFiles {
  std::string report;
  OptimizeCliOptions optimize;
  PictureCliOptions pictures;
};

/// Where the outputs of one input go (batch: folders + suffixes; empty = not asked for).
struct ParamOutputs {
  std::string obj;
  JobExtras extras;
};

/// Per-corner coordinates as OBJ texture vertices: corners of one mesh vertex with the same coordinates share a vt.
void corner_uv_table(const Mesh& mesh, const Eigen::MatrixX3cd& uv, Eigen::MatrixX2d& UV, Eigen::MatrixX3i& FUV) {
  std::vector<std::vector<std::pair<Complex, int>>> per_vertex(mesh.num_vertices());
  std::vector<Complex> table;
  FUV.resize(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      auto& list = per_vertex[mesh.F()(f, c)];
      int id = -1;
      for (const auto& [z, i] : list)
        if (z == uv(f, c)) id = i;
      if (id < 0) {
        id = static_cast<int>(table.size());
        table.push_back(uv(f, c));
        list.emplace_back(uv(f, c), id);
      }
      FUV(f, c) = id;
    }
  UV.resize(static_cast<Eigen::Index>(table.size()), 2);
  for (std::size_t i = 0; i < table.size(); ++i) UV.row(static_cast<Eigen::Index>(i)) << table[i].real(), table[i].imag();
}

/// The per-corner values as the OBJ stores them (the vt table of corner_uv_table read back per corner).
Eigen::MatrixX3cd corner_values(const Eigen::MatrixX2d& UV, const Eigen::MatrixX3i& FUV) {
  Eigen::MatrixX3cd written(FUV.rows(), 3);
  for (Eigen::Index f = 0; f < FUV.rows(); ++f)
    for (int c = 0; c < 3; ++c) written(f, c) = Complex(UV(FUV(f, c), 0), UV(FUV(f, c), 1));
  return written;
}

/// "obj" or "ply", the formats that hold per-corner texture coordinates. \throw InputError otherwise.
std::string param_output_format(const std::string& path) {
  const std::string format = mesh_output_format(path);
  if (format != "obj" && format != "ply")
    throw InputError(
        path, 0,
        "a parameterization is written as .obj (vt) or .ply (texcoord); ." + format + " holds no texture coordinates");
  return format;
}

/// The map as binary PLY: the triangles with `texcoord` (float32) per corner. Returns the largest rounding of a
/// coordinate to float32, in grid units.
double write_param_ply(const std::string& path, const Mesh& mesh, const Eigen::MatrixX2d& UV,
                       const Eigen::MatrixX3i& FUV) {
  PolygonSoup soup = PolygonSoup::from_triangles(mesh.V(), mesh.F());
  soup.uv = UV;
  soup.face_uv.reserve(soup.face_vertices.size());
  for (Eigen::Index f = 0; f < FUV.rows(); ++f)
    for (int c = 0; c < 3; ++c) soup.face_uv.push_back(FUV(f, c));
  write_ply(path, soup);
  return (UV - UV.cast<float>().cast<double>()).cwiseAbs().maxCoeff();
}

nlohmann::json run_param(const std::string& input, const ParamOutputs& out, const ParamCmdOptions& opt,
                         ProgressSink& progress) {
  PipelineOptions po;
  apply_optimize_options(opt.optimize, po);
  validate(po);
  check_plot_request(out.extras, po.optimize);
  const RenderOptions render_options = picture_render_options(opt.pictures);  // bad --size/--view fail now
  const std::vector<ViewCamera> views = picture_views(opt.pictures);
  const std::string format = param_output_format(out.obj);

  const FeatureFile feature_file = read_feature_file(opt.optimize.features_file);  // malformed: fails before any work
  StageMeter meter;
  FileVertices file_vertices;  // the OBJ keeps the input's vertex numbers, unreferenced vertices included
  const Mesh mesh = load_mesh(input, progress, file_vertices, /*written_back=*/true);
  po.param.features.given = given_features(feature_file, mesh, file_vertices.mesh_of);
  const StageCost read = meter.lap();
  ParamJob job = parameterize_mesh(mesh, po, progress);
  job.seconds.insert(job.seconds.begin(), {"read", read.seconds});
  job.peak_bytes.insert(job.peak_bytes.begin(), {"read", read.peak_bytes});
  const Mesh& map_mesh = job.mesh(mesh);  // the input, or its refinement for the curve constraints
  Eigen::MatrixX2d UV;
  Eigen::MatrixX3i FUV;
  corner_uv_table(map_mesh, job.map.uv, UV, FUV);
  nlohmann::json report = param_report(mesh, job, corner_values(UV, FUV), input);
  report["output"] = out.obj;
  // Checked before anything is written: a map that is not seamless is an error, not a file.
  if (!report["parameterization"]["seamless"].get<bool>())
    throw NumericalError("param", "the parameterization is not seamless (max transition error " +
                                      std::to_string(report["parameterization"]["max_transition_error"].get<double>()) +
                                      "); nothing written");
  meter.restart();
  // The file's own vertices (unreferenced ones included, same numbers) first, then the refinement's midpoints.
  const int n_file = static_cast<int>(file_vertices.positions.rows()), n_mesh = mesh.num_vertices();
  const int n_added = map_mesh.num_vertices() - n_mesh;
  Eigen::MatrixX3d positions(n_file + n_added, 3);
  positions.topRows(n_file) = file_vertices.positions;
  positions.bottomRows(n_added) = map_mesh.V().bottomRows(n_added);
  Eigen::MatrixX3i file_faces(map_mesh.num_faces(), 3);
  for (int f = 0; f < map_mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int v = map_mesh.F()(f, c);
      file_faces(f, c) = v < n_mesh ? file_vertices.of_mesh[static_cast<std::size_t>(v)] : n_file + v - n_mesh;
    }
  if (format == "ply")  // the report's numbers are of the exact (OBJ) coordinates; the float32 rounding is said
    report["texcoord_float32_rounding"] = write_param_ply(out.obj, map_mesh, UV, FUV);
  else
    write_obj_with_uv(out.obj, positions, file_faces, UV, FUV);
  add_report_stage(report, "write", meter.lap());
  return finish_job(
      "param", input, out.obj, out.extras, map_mesh, job.map, nullptr, report,
      [&](const std::string& png) { write_parameterization_png(png, map_mesh, job.map, views, render_options); });
}

void register_param(CLI::App* cmd, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<ParamCmdOptions>();
  add_mesh_inputs(*cmd, *opt,
                  "Output: .obj with per-corner vt (Blender, MeshLab and most tools read it), or .ply (binary) with "
                  "per-corner 'texcoord' (float32, as MeshLab reads it; Blender's PLY importer ignores it) (one "
                  "input), or a folder (several inputs); default: next to the input as NAME.param.obj");
  auto* h = cmd->add_option("--edge-length", opt->optimize.edge_length, "Target quad edge length h in model units")
                ->check(CLI::PositiveNumber);
  cmd->add_option("--faces,--quads", opt->optimize.quads,
                  "Target number of quads N, hit within 2 % of the map's quad count (h set so that the map before "
                  "its rounding has N quads, solved once more at a corrected h when missed); --quads is its old name")
      ->check(CLI::PositiveNumber)
      ->excludes(h);
  cmd->add_option("--lattice", opt->optimize.lattice,
                  "Period lattice (4.2.2): unit = Z[i]; coarse = 2Z[i] (all branch points integral); rotated = "
                  "(1+i)Z[i] (odd branch points integral, even ones fixed up)")
      ->check(CLI::IsMember({"unit", "coarse", "rotated"}))
      ->capture_default_str();
  cmd->add_option("--report", opt->report, "Write a JSON report (one input) or a folder for NAME.param.json files");
  add_optimize_options(*cmd, opt->optimize);
  add_picture_options(*cmd, opt->pictures, "PNG of the map: checkerboard (one square = one quad), seams, branch points");
  add_global_options(*cmd, global);
  run_on_inputs(*cmd, global, exit_code, opt->inputs,
                {"faces", "branch_points", "h_sym", "E_D", "E_H", "flipped_triangles", "seamless"},
                [opt](const std::string& input, bool batch, ProgressSink& progress) {
                  const ParamOutputs out{output_path(input, opt->output, batch, ".param.obj"),
                                         job_extras(input, batch, opt->report, opt->pictures, ".param", ".param.png")};
                  return run_param(input, out, *opt, progress);
                });
}

const CommandRegistrar registrar{
    40, "param", register_param,
    "Seamless QuadCover parameterization (thesis ch. 2-4) guided by the curvature cross field: OBJ with v, "
    "per-corner vt in grid units (integer iso-lines = quad edges) and f v/vt. Density: --edge-length h or "
    "--faces N; default h = 2 x the mean edge length (about #faces/9 quads), or finer so that there are at least "
    "30 quads per branch point of the field and every boundary loop is at least 4 quad edges around"};

}  // namespace

}  // namespace quadcover::cli
