// `quadcover render MESH... -o OUT.png`: pictures of a parameterized OBJ (checkerboard from its `vt`, seams, cones),
// of a quad/polygon mesh (wireframe over shading) or of the parameter domain (--uv-layout), rendered offscreen.
#include <iostream>
#include <sstream>

#include "cli/common.h"
#include "cli/pictures.h"
#include "cli/registry.h"
#include "common/errors.h"
#include "io/read_mesh.h"
#include "render/html_report.h"
#include "render/render_mesh.h"
#include "render/scene.h"

namespace quadcover::cli {

namespace {

struct RenderCmdOptions : MeshFiles {
  std::string view = "front";
  std::string size = "800x800";
  std::string texture = "checker";
  double period = 1.0;
  int supersample = 3;
  bool uv_layout = false;
  bool wireframe = false;
  std::string report_html;  // self-contained HTML page with an interactive view
  std::string metrics;      // a JSON report (param/remesh/metrics --report) shown in the page
  std::string quads;        // a quad mesh shown next to the input in the page
};

nlohmann::json render_one(const std::string& input, const std::string& output, const RenderCmdOptions& opt) {
  const auto [w, h] = parse_size(opt.size);
  const std::vector<ViewCamera> views = parse_views(opt.view);
  const MeshScene scene = scene_from_soup(read_mesh(input));
  nlohmann::json j{{"file", input}, {"output", output}, {"faces", scene.polygons.size()}};
  if (output.empty()) return j;  // only the HTML page was asked for
  Image image;
  if (opt.uv_layout) {
    if (scene.uv.rows() == 0)
      throw InputError(input, 0, "--uv-layout needs per-corner texture coordinates (`vt` on every face corner)");
    UvLayoutOptions lo;
    lo.width = w;
    lo.height = h;
    lo.supersample = opt.supersample;
    // The classification every report uses (param/seams.h): what is drawn red is what is counted.
    const FlipReport flips = flipped_triangles(triangle_areas(scene), scene.uv);
    image = render_uv_layout(scene.uv, flips, lo);
    j["flipped_triangles"] = flips.flipped;
    j["collapsed_triangles"] = flips.collapsed;
    j["non_positive_triangles"] = flips.non_positive;
  } else {
    RenderOptions ro;
    ro.width = w;
    ro.height = h;
    ro.supersample = opt.supersample;
    ro.texture_period = opt.period;
    ro.texture = opt.texture == "grid"   ? SurfaceTexture::GridLines
                 : opt.texture == "none" ? SurfaceTexture::None
                                         : SurfaceTexture::Checkerboard;
    const bool polygons = opt.wireframe || !scene.all_triangles;
    std::vector<BranchPoint> cones;
    if (!polygons && scene.uv.rows() > 0) {
      cones = cones_from_uv(scene.F, scene.uv);  // the reports' computation (metrics/param_quality.h)
      j["seam_edges"] = uv_seam_edges(scene.F, scene.uv).size();
      j["cones"] = cones.size();
    }
    std::vector<Image> images;
    for (const ViewCamera& cam : views) {
      ro.camera = cam;
      images.push_back(polygons ? render_polygon_mesh(scene.V, scene.polygons, ro)
                                : render_textured_mesh(scene.V, scene.F, scene.uv, cones, ro));
    }
    image = images.size() == 1 ? std::move(images[0]) : tile_horizontally(images);
    j["mode"] = polygons ? "wireframe" : (scene.uv.rows() > 0 ? "textured" : "shaded");
  }
  if (!output.empty()) {
    write_png(output, image);
    j["width"] = image.width;
    j["height"] = image.height;
  }
  return j;
}

void write_report_page(const std::string& input, const std::string& html, const RenderCmdOptions& opt) {
  const MeshScene scene = scene_from_soup(read_mesh(input));
  HtmlReport report;
  report.title = "quadcover: " + input;
  if (!opt.metrics.empty()) {
    try {
      report.metrics = nlohmann::json::parse(read_file_bytes(opt.metrics));
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError(opt.metrics, 0, std::string("not a JSON report: ") + e.what());
    }
    report.figures = figures_from_report(report.metrics);
  }
  HtmlMesh surface{input, scene.V, scene.polygons, scene.uv, !scene.all_triangles || opt.wireframe};
  report.meshes.push_back(std::move(surface));
  if (!scene.all_triangles)
    for (auto& fig : polygon_mesh_figures(scene.V, scene.polygons)) report.figures.push_back(std::move(fig));
  if (!opt.quads.empty()) {
    const MeshScene quads = scene_from_soup(read_mesh(opt.quads));
    report.meshes.push_back({opt.quads, quads.V, quads.polygons, {}, true});
    for (auto& fig : polygon_mesh_figures(quads.V, quads.polygons)) report.figures.push_back(std::move(fig));
  }
  write_html_report(html, report);
}

void register_render(CLI::App* cmd, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<RenderCmdOptions>();
  add_mesh_inputs(*cmd, *opt,
                  "Output PNG (one input) or folder (several inputs: <name>.png inside; default: next to each input)",
                  "Input meshes (OBJ with optional vt, OFF, PLY, STL) or folders of them");
  cmd->add_option("--view", opt->view,
                  "Camera: front, side, top, back, bottom, iso, all (front+side+top side by side), or AZ,EL in "
                  "degrees (default front)");
  cmd->add_flag(
      "--uv-layout", opt->uv_layout,
      "Draw the parameter domain instead (flipped and collapsed triangles in red, as the reports count them)");
  cmd->add_flag("--wireframe", opt->wireframe, "Draw edges over flat shading (default for non-triangle meshes)");
  cmd->add_option("--size", opt->size, "Image size WxH in pixels per view (default 800x800)");
  cmd->add_option("--texture", opt->texture, "Surface texture from the UVs: checker, grid or none (default checker)")
      ->check(CLI::IsMember({"checker", "grid", "none"}));
  cmd->add_option("--period", opt->period, "UV units per checker square or grid cell (default 1: one quad)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--supersample", opt->supersample, "Antialiasing samples per pixel side (default 3)")
      ->check(CLI::Range(1, 8));
  cmd->add_option("--report-html", opt->report_html,
                  "Also write a self-contained HTML page: metrics, plots and interactive 3D views (opens offline)");
  cmd->add_option("--metrics", opt->metrics, "JSON report (from param/remesh/metrics --report) to show in the page")
      ->check(CLI::ExistingFile);
  cmd->add_option("--quads", opt->quads, "Quad mesh to show next to the input in the page")->check(CLI::ExistingFile);
  add_global_options(*cmd, global);
  cmd->callback([opt, &global, &exit_code] {
    BatchSpec spec;
    spec.inputs = opt->inputs;
    spec.summary_columns = {"faces", "mode", "output"};
    const bool batch = is_batch(opt->inputs);
    if (!batch && opt->output.empty() && opt->report_html.empty())
      throw InputError("-o", 0, "an output is required (-o OUT.png and/or --report-html OUT.html)");
    if (batch && !opt->report_html.empty())
      throw InputError("--report-html", 0, "the HTML report takes a single input mesh");
    exit_code = run_batch(spec, global, [opt, batch](const std::string& input, ProgressSink&) {
      const std::string out = batch ? batch_output_path(input, opt->output, ".png") : opt->output;
      nlohmann::json j = render_one(input, out, *opt);
      if (!opt->report_html.empty()) {
        write_report_page(input, opt->report_html, *opt);
        j["report_html"] = opt->report_html;
      }
      return j;
    });
  });
}

const CommandRegistrar registrar{
    60, "render", register_render,
    "Render PNG pictures offscreen: a parameterized OBJ with a checkerboard from its per-corner `vt`, seams "
    "(orange) and cones (blue: index 1/4, red: -1/4, cyan/magenta: ±1/2, grey: other, e.g. whole turns); a "
    "quad/polygon mesh as wireframe; or the UV layout"};

}  // namespace

}  // namespace quadcover::cli
