// `quadcover remesh MESH -o QUADS.obj`: the whole pipeline — frame field (thesis ch. 5) → QuadCover
// parameterization (ch. 2-4) → quad extraction — with the Table 7.1 metrics of the result.
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
#include "metrics/vertex_quality.h"
#include "pipeline/job_report.h"
#include "pipeline/remesh_mesh.h"
#include "render/pipeline_pictures.h"

namespace quadcover::cli {

namespace {

struct RemeshOptions : MeshFiles {
  std::string report;
  std::string param_output;
  bool ply_quality = false;
  QuadSmoothingOptions smoothing;
  bool boundary_quads = ExtractOptions{}.quadrangulate_boundary;
  OptimizeCliOptions optimize;
  PictureCliOptions pictures;
};

/// Where the outputs of one input go (batch: folders + suffixes; empty = not asked for).
struct RemeshOutputs {
  std::string quads, param;
  JobExtras extras;
};

void write_param_obj(const std::string& path, const Mesh& mesh, const Eigen::MatrixX3cd& uv) {
  Eigen::MatrixX2d UV(3 * mesh.num_faces(), 2);
  Eigen::MatrixX3i FUV(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      UV.row(3 * f + c) << uv(f, c).real(), uv(f, c).imag();
      FUV(f, c) = 3 * f + c;
    }
  write_obj_with_uv(path, mesh.V(), mesh.F(), UV, FUV);
}

/// The quad mesh as binary PLY with the per-vertex `quality` (worst corner angle deviation, degrees) and `valence`
/// of metrics/vertex_quality.h.
void write_quality_ply(const std::string& path, const QuadMesh& quads) {
  const VertexQuality q = vertex_quality(quads.V, quads.faces);
  write_ply(path, PolygonSoup::from_polygons(quads.V, quads.faces),
            {{"quality", q.worst_angle_deviation, false}, {"valence", q.valence.cast<double>(), true}});
}

nlohmann::json run_remesh(const std::string& input, const RemeshOutputs& out, const RemeshOptions& opt,
                          ProgressSink& progress) {
  PipelineOptions po;
  po.smoothing = opt.smoothing;
  po.extraction.quadrangulate_boundary = opt.boundary_quads;
  apply_optimize_options(opt.optimize, po);
  validate(po);
  check_plot_request(out.extras, po.optimize);
  if (mesh_output_format(out.quads) != "ply" && opt.ply_quality)  // an unknown extension fails before any work
    throw InputError(out.quads, 0, "--ply-quality needs a .ply output");
  const RenderOptions render_options = picture_render_options(opt.pictures);  // bad --size/--view fail now
  const std::vector<ViewCamera> views = picture_views(opt.pictures);
  const FeatureFile feature_file = read_feature_file(opt.optimize.features_file);  // malformed: fails before any work
  StageMeter meter;
  FileVertices file_vertices;
  const Mesh mesh = load_mesh(input, progress, file_vertices, /*written_back=*/false, /*new_surface=*/true);
  po.param.features.given = given_features(feature_file, mesh, file_vertices.mesh_of);
  const StageCost read = meter.lap();
  RemeshJob job;
  try {
    job = remesh_mesh(mesh, po, progress);
  } catch (const InputError& e) {
    if (e.file() != "density") throw;
    throw InputError(input, 0, std::string(e.what()).substr(9) + " (--faces N or --edge-length h)");
  }
  job.param.seconds.insert(job.param.seconds.begin(), {"read", read.seconds});
  job.param.peak_bytes.insert(job.param.peak_bytes.begin(), {"read", read.peak_bytes});
  nlohmann::json report = remesh_report(mesh, job, input);
  report["output"] = out.quads;
  meter.restart();
  const QuadMesh& quads = job.extraction.mesh;
  if (opt.ply_quality)
    write_quality_ply(out.quads, quads);
  else if (const std::size_t split = write_polygon_mesh(out.quads, quads.V, quads.faces); split > 0)
    report["warnings"].push_back(std::to_string(split) + " polygons were split into triangles for the STL output");
  if (!out.param.empty()) write_param_obj(out.param, job.param.mesh(mesh), job.param.map.uv);
  add_report_stage(report, "write", meter.lap());
  return finish_job("remesh", input, out.quads, out.extras, job.param.mesh(mesh), job.param.map, &quads, report,
                    [&](const std::string& png) { write_quad_mesh_png(png, quads, views, render_options); });
}

void register_remesh(CLI::App* cmd, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<RemeshOptions>();
  add_mesh_inputs(*cmd, *opt,
                  "Output mesh, format by extension: .obj, .off, .ply (binary), .stl (triangulated) (one input), or "
                  "a folder (several inputs); default: next to the input as NAME.quad.obj");
  cmd->add_flag("--ply-quality", opt->ply_quality,
                "Write the quad mesh as binary PLY (.ply output; NAME.quad.ply in batches) with per-vertex "
                "'quality' = the worst corner angle deviation from 90 degrees at the vertex (degrees; for a non-quad "
                "n-gon from its regular angle) and 'valence' = the vertex's edge count");
  auto* nv = cmd->add_option("--faces,--quads,--vertices", opt->optimize.quads,
                             "Target number of quads N, hit within 2 % of the map's quad count (on a closed mesh the "
                             "quad mesh has about as many vertices); --quads and --vertices are its old names")
                 ->check(CLI::PositiveNumber);
  cmd->add_option("--edge-length", opt->optimize.edge_length, "Target quad edge length in model units")
      ->check(CLI::PositiveNumber)
      ->excludes(nv);
  cmd->add_option("--lattice", opt->optimize.lattice, "Period lattice (4.2.2): unit, coarse or rotated")
      ->check(CLI::IsMember({"unit", "coarse", "rotated"}))
      ->capture_default_str();
  add_optimize_options(*cmd, opt->optimize);
  cmd->add_option("--smooth-quads", opt->smoothing.iterations,
                  "Rounds of tangential smoothing of the quad mesh on the input surface after extraction (0 = off: "
                  "the vertices stay at the integer points of the map)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--smooth-rigidity", opt->smoothing.rigidity,
                  "Smoothing target: 1 evens out edge lengths, 0 only squares up the quads")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--boundary-quads", opt->boundary_quads,
                  "Make the polygons that the boundary clips out of grid cells into quads: a triangle cut off where "
                  "an iso-line meets the boundary at a shallow angle is collapsed onto it, odd pairs are merged, odd "
                  "polygons get a vertex on the boundary, and each is split into convex quads (the report's "
                  "extraction.boundary_* counts them); false keeps the clipped polygons of the integer grid "
                  "(true/false)")
      ->capture_default_str();
  cmd->add_option("--report", opt->report, "Write the JSON report (one input) or a folder for NAME.remesh.json");
  cmd->add_option("--param", opt->param_output,
                  "Also write the parameterization as OBJ with per-corner vt (one input) or a folder for them");
  add_picture_options(*cmd, opt->pictures, "PNG of the quad mesh: wireframe over flat shading");
  add_global_options(*cmd, global);
  run_on_inputs(
      *cmd, global, exit_code, opt->inputs,
      {"vertices", "non_quads", "rsd_edge_length", "rsd_corner_angle", "irregular_vertices", "arap", "manifold"},
      [opt](const std::string& input, bool batch, ProgressSink& progress) {
        const std::string quads = opt->ply_quality ? ".quad.ply" : ".quad.obj";
        const RemeshOutputs out{output_path(input, opt->output, batch, quads),
                                optional_output_path(input, opt->param_output, batch, ".param.obj"),
                                job_extras(input, batch, opt->report, opt->pictures, ".remesh", ".quad.png")};
        return run_remesh(input, out, *opt, progress);
      });
}

const CommandRegistrar registrar{
    60, "remesh", register_remesh,
    "Quad remeshing: frame field -> QuadCover parameterization -> quad extraction along the integer iso-lines; "
    "writes the quad mesh (OBJ) and optionally a JSON report with the Table 7.1 metrics"};

}  // namespace

}  // namespace quadcover::cli
