// `quadcover remesh MESH -o QUADS.obj`: the whole pipeline — frame field (thesis ch. 5) → QuadCover
// parameterization (ch. 2-4) → quad extraction — with the Table 7.1 metrics of the result.
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "cli/common.h"
#include "param/seams.h"
#include "cli/optimize_options.h"
#include "cli/pictures.h"
#include "cli/registry.h"
#include "common/errors.h"
#include "field/compute_frame_field.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "metrics/report.h"
#include "param/parameterize.h"
#include "quad/extract_quads.h"
#include "quad/smooth_quads.h"
#include "render/pipeline_pictures.h"

namespace quadcover::cli {

namespace {

struct RemeshOptions {
  std::vector<std::string> inputs;
  std::string output;
  std::string report;
  std::string param_output;
  int vertices = 0;
  double edge_length = 0;
  std::string lattice = "rotated";
  QuadSmoothingOptions smoothing;
  OptimizeCliOptions optimize;
  PictureCliOptions pictures;
};

/// Where the outputs of one input go (batch: folders + suffixes; empty = not asked for).
struct RemeshOutputs {
  std::string quads, report, param, png, html, plot;
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

nlohmann::json run_remesh(const std::string& input, const RemeshOutputs& out, const RemeshOptions& opt,
                          ProgressSink& progress) {
  const std::string& output = out.quads;
  if (opt.vertices > 0 && opt.edge_length > 0)
    throw InputError("--vertices/--edge-length", 0, "give either --vertices or --edge-length, not both");
  if (!out.plot.empty() && opt.optimize.optimize == "none")
    throw InputError("--plot", 0, "the optimization plot needs --optimize relocate or full");
  const RenderOptions render_options = picture_render_options(opt.pictures);  // bad --size/--view fail now
  const std::vector<ViewCamera> views = picture_views(opt.pictures);
  using Clock = std::chrono::steady_clock;
  Report report;
  report.input = input;
  auto t = Clock::now();
  auto lap = [&](const char* stage) {
    const auto now = Clock::now();
    report.seconds[stage] = std::chrono::duration<double>(now - t).count();
    t = now;
  };
  const Mesh mesh = build_mesh(read_mesh(input)).mesh;
  lap("read");
  ParamOptions po;
  po.lattice = parse_lattice(opt.lattice);
  po.edge_length = opt.edge_length;
  // A closed quad mesh has about as many vertices as faces (V - F = χ - E + 2F ... = χ + F - E, E = 2F).
  po.target_quads = opt.vertices;
  apply_param_options(opt.optimize, po);
  const FrameFieldResult detailed = compute_frame_field_detailed(mesh, field_options(opt.optimize), progress);
  lap("field");
  fix_default_density(mesh, detailed.field, po);  // one scale for the optimization, keep-better and the map
  nlohmann::json optimize;
  const FrameField field = run_optimize(mesh, detailed, opt.optimize, po, progress, optimize);
  lap("optimize");
  const Parameterization P = parameterize_best(mesh, detailed.field, field, opt.optimize, po, progress, optimize);
  lap("param");
  // The signed parameter area is the number of quads the map can hold; below a few there is nothing to extract
  // (too coarse a density, or a map folded onto itself by a field without branch points, e.g. a flat fan).
  const double area = flipped_triangles(mesh, P.uv).parameter_area;
  if (area < 4)
    throw InputError(input, 0,
                     "the map holds about " + std::to_string(static_cast<int>(std::lround(std::max(0.0, area)))) +
                         " quads, too few to extract a quad mesh; ask for more with --vertices N or a smaller "
                         "--edge-length" +
                         (P.branch_points.empty() && mesh.num_boundary_loops() > 0
                              ? " (if the map folds onto itself, the field's singularities are whole turns)"
                              : ""));
  ExtractionResult ex = extract_quads(mesh, P, ExtractOptions{}, progress);
  lap("extract");
  const QuadSmoothingReport smoothing = smooth_quads(ex.mesh, mesh, P, opt.smoothing, progress);
  lap("smooth");
  report.parameterization = param_quality(mesh, P);
  report.extraction = ex.report;
  report.quad_mesh = quad_quality(ex.mesh);
  report.surface_distance = surface_distance(ex.mesh.V, ex.mesh.faces, mesh.V(), mesh.F());
  lap("metrics");
  report.values["edge_length"] = P.edge_length;
  report.values["field_branch_points"] = static_cast<double>(P.branch_points.size());
  report.values["input_faces"] = mesh.num_faces();
  if (ex.mesh.num_faces() == 0)
    throw NumericalError("remesh", "the extraction produced no faces (the map is broken)");
  write_polygon_obj(output, ex.mesh.V, ex.mesh.faces);
  if (!out.param.empty()) write_param_obj(out.param, mesh, P.uv);
  lap("write");
  nlohmann::json j = to_json(report);
  j["optimize"] = optimize;
  j["rounding"] = rounding_to_json(po, P);
  j["relaxation"] = relaxation_to_json(P);
  j["stiffening"] = stiffening_to_json(P);
  j["quad_smoothing"] = quad_smoothing_to_json(opt.smoothing, smoothing);
  if (!out.report.empty()) write_json_atomically(out.report, j);
  if (!out.png.empty()) write_quad_mesh_png(out.png, ex.mesh, views, render_options);
  if (!out.plot.empty()) write_optimization_plot(out.plot, optimize);
  if (!out.html.empty())
    write_pipeline_report(out.html, "quadcover remesh: " + input, mesh, &P, &ex.mesh, j,
                          &*report.parameterization);
  nlohmann::json brief = optimize;
  brief.erase("log");  // in the --report file; the summary stays short
  const auto& q = *report.quad_mesh;
  return {{"output", output},
          {"vertices", q.vertices},
          {"faces", q.faces},
          {"non_quads", q.non_quads},
          {"rsd_edge_length", q.rsd_edge_length},
          {"rsd_corner_angle", q.rsd_corner_angle},
          {"irregular_vertices", q.irregular_vertices},
          {"branch_points", report.parameterization->branch_points},
          {"arap", report.parameterization->arap},
          {"flipped_triangles", report.parameterization->flipped_triangles},
          {"manifold", q.topology.manifold()},
          {"closed", q.topology.closed()},
          {"distance_max", report.surface_distance->max},
          {"repairs", ex.report.failed_traces + ex.report.dropped_faces + ex.report.torn_seams},
          {"E_D", report.parameterization->energy_curl},
          {"E_H", report.parameterization->energy_harmonic},
          {"optimize", brief},
          {"rounding", j["rounding"]},
          {"seconds", report.seconds}};
}

void register_remesh(CLI::App& app, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<RemeshOptions>();
  CLI::App* cmd = app.add_subcommand(
      "remesh",
      "Quad remeshing: frame field -> QuadCover parameterization -> quad extraction along the integer iso-lines; "
      "writes the quad mesh (OBJ) and optionally a JSON report with the Table 7.1 metrics");
  add_input_option(*cmd, opt->inputs);
  cmd->add_option("-o,--output", opt->output,
                  "Output OBJ (one input) or folder (several inputs); default: next to the input as NAME.quad.obj");
  auto* nv = cmd->add_option("--vertices", opt->vertices, "Target number of output vertices (≈ quads on a closed mesh)")
                 ->check(CLI::PositiveNumber);
  cmd->add_option("--edge-length", opt->edge_length, "Target quad edge length in model units")
      ->check(CLI::PositiveNumber)
      ->excludes(nv);
  cmd->add_option("--lattice", opt->lattice, "Period lattice (4.2.2): unit, coarse or rotated")
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
  cmd->add_option("--report", opt->report, "Write the JSON report (one input) or a folder for NAME.remesh.json");
  cmd->add_option("--param", opt->param_output,
                  "Also write the parameterization as OBJ with per-corner vt (one input) or a folder for them");
  add_picture_options(*cmd, opt->pictures, "PNG of the quad mesh: wireframe over flat shading");
  add_global_options(*cmd, global);
  cmd->callback([opt, &global, &exit_code] {
    BatchSpec spec;
    spec.inputs = opt->inputs;
    spec.summary_columns = {"vertices", "non_quads", "rsd_edge_length", "rsd_corner_angle", "irregular_vertices",
                            "arap", "manifold"};
    const bool batch = is_batch(opt->inputs);
    exit_code = run_batch(spec, global, [opt, batch](const std::string& input, ProgressSink& progress) {
      const std::string output =
          batch || opt->output.empty() ? batch_output_path(input, opt->output, ".quad.obj") : opt->output;
      auto path = [&](const std::string& o, const char* suffix) {
        return o.empty() ? std::string() : batch ? batch_output_path(input, o, suffix) : o;
      };
      const RemeshOutputs out{output,
                              path(opt->report, ".remesh.json"),
                              path(opt->param_output, ".param.obj"),
                              path(opt->pictures.png, ".quad.png"),
                              path(opt->pictures.report_html, ".remesh.html"),
                              path(opt->pictures.plot, ".optimize.png")};
      return run_remesh(input, out, *opt, progress);
    });
  });
}

const CommandRegistrar registrar{60, "remesh", register_remesh};

}  // namespace

}  // namespace quadcover::cli
