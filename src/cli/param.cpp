// `quadcover param MESH -o OUT.obj`: the seamless QuadCover parameterization (thesis Chapters 2-4) guided by the
// curvature frame field of Chapter 5, written as an OBJ with per-corner texture coordinates in grid units.
#include <chrono>
#include <map>
#include <nlohmann/json.hpp>

#include "cli/common.h"
#include "cli/optimize_options.h"
#include "cli/pictures.h"
#include "cli/registry.h"
#include "common/errors.h"
#include "field/compute_frame_field.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "mesh/mesh.h"
#include "metrics/param_quality.h"
#include "metrics/report.h"
#include "param/parameterize.h"
#include "param/seams.h"
#include "render/pipeline_pictures.h"

namespace quadcover::cli {

namespace {

struct ParamCmdOptions {
  std::vector<std::string> inputs;
  std::string output;
  std::string report;
  double edge_length = 0;
  int quads = 0;
  std::string lattice = "rotated";
  OptimizeCliOptions optimize;
  PictureCliOptions pictures;
  bool align = true;
};

/// Where the outputs of one input go (batch: folders + suffixes; empty = not asked for).
struct ParamOutputs {
  std::string obj, report, png, html, plot;
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

nlohmann::json run_param(const std::string& input, const ParamOutputs& out, const ParamCmdOptions& opt,
                         ProgressSink& progress) {
  const std::string& output = out.obj;
  if (opt.edge_length > 0 && opt.quads > 0)
    throw InputError("--edge-length/--quads", 0, "give either --edge-length or --quads, not both");
  ParamOptions po;
  po.lattice = parse_lattice(opt.lattice);
  po.edge_length = opt.edge_length;
  po.target_quads = opt.quads;
  po.align_curves = opt.align;
  apply_param_options(opt.optimize, po);
  if (!out.plot.empty() && opt.optimize.optimize == "none")
    throw InputError("--plot", 0, "the optimization plot needs --optimize relocate or full");
  const RenderOptions render_options = picture_render_options(opt.pictures);  // bad --size/--view fail now
  const std::vector<ViewCamera> views = picture_views(opt.pictures);

  using Clock = std::chrono::steady_clock;
  nlohmann::json seconds = nlohmann::json::object();
  auto t = Clock::now();
  auto lap = [&](const char* stage) {
    const auto now = Clock::now();
    seconds[stage] = std::chrono::duration<double>(now - t).count();
    t = now;
  };
  const Mesh mesh = build_mesh(read_mesh(input)).mesh;
  lap("read");
  nlohmann::json optimize;
  const FrameFieldResult detailed = compute_frame_field_detailed(mesh, field_options(opt.optimize), progress);
  lap("field");
  fix_default_density(mesh, detailed.field, po);  // one scale for the optimization, keep-better and the map
  const FrameField field = run_optimize(mesh, detailed, opt.optimize, po, progress, optimize);
  lap("optimize");
  const Parameterization P = parameterize_best(mesh, detailed.field, field, opt.optimize, po, progress, optimize);
  for (const auto& [stage, s] : P.stage_seconds) seconds["param_" + stage] = s;
  t = Clock::now();

  Eigen::MatrixX2d UV;
  Eigen::MatrixX3i FUV;
  corner_uv_table(mesh, P.uv, UV, FUV);
  write_obj_with_uv(output, mesh.V(), mesh.F(), UV, FUV);
  lap("write");

  // Measured on the written data: the vt table and the face/vt indices.
  Eigen::MatrixX3cd written(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) written(f, c) = Complex(UV(FUV(f, c), 0), UV(FUV(f, c), 1));
  const SeamReport seams = measure_seams(mesh, written, 1e-9);
  const FlipReport flips = flipped_triangles(mesh, written);

  nlohmann::json bps = nlohmann::json::array();
  int b_even = 0, b_odd = 0;
  for (const BranchPoint& b : P.branch_points) {
    const bool even = ((b.quarter_index % 4) + 4) % 4 == 2;
    (even ? b_even : b_odd) += 1;
    bps.push_back({{"vertex", b.vertex}, {"quarter_index", b.quarter_index}, {"index", b.quarter_index / 4.0}});
  }
  nlohmann::json curves = nlohmann::json::array();
  double worst_curve = 0;
  for (const auto& c : P.aligned_curves) {
    curves.push_back({{"edges", c.edges.size()},
                      {"coordinate", c.coordinate == 0 ? "u" : "v"},
                      {"value", c.value},
                      {"max_deviation", c.max_deviation}});
    worst_curve = std::max(worst_curve, c.max_deviation);
  }
  nlohmann::json report = {{"file", input},
                           {"output", output},
                           {"vertices", mesh.num_vertices()},
                           {"faces", mesh.num_faces()},
                           {"genus", mesh.genus()},
                           {"boundary_loops", mesh.num_boundary_loops()},
                           {"lattice", to_string(po.lattice)},
                           {"rounding", rounding_to_json(po, P)},
                           {"optimize", optimize},
                           {"edge_length", P.edge_length},
                           {"parameter_area", flips.parameter_area},
                           {"branch_points", bps},
                           {"b_odd", b_odd},
                           {"b_even", b_even},
                           {"unfixed_even_branch_points", P.unfixed_even_branch_points},
                           {"h_sym", P.h_sym},
                           {"E_D", P.energy_curl},
                           {"E_H", P.energy_harmonic},
                           {"E_R", P.relaxation.energy},
                           {"E_S", P.stiffening.energy},
                           {"relaxation", relaxation_to_json(P)},
                           {"stiffening", stiffening_to_json(P)},
                           {"untangling",
                            {{"iterations", P.untangling.iterations},
                             {"polish_iterations", P.untangling.polish_iterations},
                             {"non_positive_before", P.untangling.non_positive_before},
                             {"non_positive_after", P.untangling.non_positive_after},
                             {"stuck_faces", P.untangling.stuck_faces},
                             {"unresolved_faces", P.untangling.unresolved_faces},
                             {"min_det", P.untangling.min_det},
                             {"seconds", P.untangling.seconds},
                             {"E_U", P.untangling.energy}}},
                           {"flipped_triangles", flips.flipped},
                           {"flipped_faces", flips.flipped_faces},
                           {"degenerate_triangles", flips.collapsed},
                           {"collapsed_triangles", flips.collapsed},
                           {"non_positive_triangles", flips.non_positive},
                           {"seamless", seams.seamless},
                           {"max_transition_error", seams.max_transition_error},
                           {"parameter_extent", seams.parameter_extent},
                           {"cut_edges", seams.cut_edges},
                           {"aligned_curves", curves},
                           {"max_curve_deviation", worst_curve},
                           {"alignment_conflicts", P.alignment_conflicts},
                           {"seconds", seconds}};
  nlohmann::json warnings = nlohmann::json::array();
  for (int comp : P.holonomy_without_branch_points)
    warnings.push_back("component " + std::to_string(comp) +
                       ": the field turns around a handle but has no branch points; no seamless immersion exists "
                       "there (the map degenerates). Use a field with branch points (e.g. --optimize full).");
  if (!P.unfixed_even_branch_points.empty())
    warnings.push_back(std::to_string(P.unfixed_even_branch_points.size()) +
                       " even branch points stay on half-integers (see unfixed_even_branch_points)");
  for (const auto& w : warnings) progress.report("param", -1, "warning: " + w.get<std::string>());
  report["warnings"] = warnings;
  if (!out.report.empty()) write_json_atomically(out.report, report);
  if (!out.png.empty()) {
    write_parameterization_png(out.png, mesh, P, views, render_options);
    report["png"] = out.png;
  }
  if (!out.plot.empty()) {
    write_optimization_plot(out.plot, optimize);
    report["plot"] = out.plot;
  }
  if (!out.html.empty()) {
    const ParamQuality quality = param_quality(mesh, P);
    nlohmann::json page = report;
    page["quality"] = to_json(quality);
    write_pipeline_report(out.html, "quadcover param: " + input, mesh, &P, nullptr, page, &quality);
    report["report_html"] = out.html;
  }
  nlohmann::json summary = report;
  summary["branch_points"] = P.branch_points.size();
  summary.erase("flipped_faces");
  summary["aligned_curves"] = P.aligned_curves.size();
  summary["optimize"].erase("log");  // in the --report file; the summary stays short
  if (!seams.seamless)
    throw NumericalError("param", "the written parameterization is not seamless (max transition error " +
                                      std::to_string(seams.max_transition_error) + ")");
  return summary;
}

void register_param(CLI::App& app, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<ParamCmdOptions>();
  CLI::App* cmd = app.add_subcommand(
      "param",
      "Seamless QuadCover parameterization (thesis ch. 2-4) guided by the curvature cross field: OBJ with v, "
      "per-corner vt in grid units (integer iso-lines = quad edges) and f v/vt. Density: --edge-length h or "
      "--quads N; default h = 2 x the mean edge length (about #faces/9 quads), or finer so that there are at least "
      "30 quads per branch point of the field");
  add_input_option(*cmd, opt->inputs);
  cmd->add_option("-o,--output", opt->output,
                  "Output OBJ (one input) or folder (several inputs); default: next to the input as NAME.param.obj");
  cmd->add_option("--edge-length", opt->edge_length, "Target quad edge length h in model units")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--quads", opt->quads, "Target number of quads N (h = sqrt(area / N))")->check(CLI::PositiveNumber);
  cmd->add_option("--lattice", opt->lattice,
                  "Period lattice (4.2.2): unit = Z[i]; coarse = 2Z[i] (all branch points integral); rotated = "
                  "(1+i)Z[i] (odd branch points integral, even ones fixed up)")
      ->check(CLI::IsMember({"unit", "coarse", "rotated"}))
      ->capture_default_str();
  cmd->add_option("--align", opt->align,
                  "Put boundary and sharp feature curves the field follows on integer iso-lines (true/false)")
      ->capture_default_str();
  cmd->add_option("--report", opt->report, "Write a JSON report (one input) or a folder for NAME.param.json files");
  add_optimize_options(*cmd, opt->optimize);
  add_picture_options(*cmd, opt->pictures, "PNG of the map: checkerboard (one square = one quad), seams, branch points");
  add_global_options(*cmd, global);
  cmd->callback([opt, &global, &exit_code] {
    BatchSpec spec;
    spec.inputs = opt->inputs;
    spec.summary_columns = {"faces", "branch_points", "h_sym", "E_D", "E_H", "flipped_triangles", "seamless"};
    const bool batch = is_batch(opt->inputs);
    exit_code = run_batch(spec, global, [opt, batch](const std::string& input, ProgressSink& progress) {
      const std::string output =
          batch || opt->output.empty() ? batch_output_path(input, opt->output, ".param.obj") : opt->output;
      auto path = [&](const std::string& o, const char* suffix) {
        return o.empty() ? std::string() : batch ? batch_output_path(input, o, suffix) : o;
      };
      const ParamOutputs out{output, path(opt->report, ".param.json"), path(opt->pictures.png, ".param.png"),
                             path(opt->pictures.report_html, ".param.html"), path(opt->pictures.plot, ".optimize.png")};
      return run_param(input, out, *opt, progress);
    });
  });
}

const CommandRegistrar registrar{40, "param", register_param};

}  // namespace

}  // namespace quadcover::cli
