#include "render/pipeline_pictures.h"

#include "render/html_report.h"

namespace quadcover {

namespace {
Image tiled(const std::vector<ViewCamera>& views, RenderOptions options, const auto& render_one) {
  std::vector<Image> images;
  for (const ViewCamera& cam : views.empty() ? std::vector<ViewCamera>{ViewCamera{}} : views) {
    options.camera = cam;
    images.push_back(render_one(options));
  }
  return images.size() == 1 ? std::move(images[0]) : tile_horizontally(images);
}
}  // namespace

void write_parameterization_png(const std::string& path, const Mesh& mesh, const Parameterization& param,
                                const std::vector<ViewCamera>& views, RenderOptions options) {
  write_png(path, tiled(views, options, [&](const RenderOptions& o) {
              return render_textured_mesh(mesh.V(), mesh.F(), param.uv, param.branch_points, o);
            }));
}

void write_quad_mesh_png(const std::string& path, const QuadMesh& quads, const std::vector<ViewCamera>& views,
                         RenderOptions options) {
  write_png(path, tiled(views, options,
                        [&](const RenderOptions& o) { return render_polygon_mesh(quads.V, quads.faces, o); }));
}

void write_pipeline_report(const std::string& path, const std::string& title, const Mesh& mesh,
                           const Parameterization* param, const QuadMesh* quads, const nlohmann::json& report,
                           const ParamQuality* quality) {
  HtmlReport page;
  page.title = title;
  page.metrics = report;
  page.figures = figures_from_report(report);
  std::vector<std::vector<int>> triangles(static_cast<std::size_t>(mesh.num_faces()));
  for (int f = 0; f < mesh.num_faces(); ++f)
    triangles[static_cast<std::size_t>(f)] = {mesh.F()(f, 0), mesh.F()(f, 1), mesh.F()(f, 2)};
  page.meshes.push_back({param ? "parameterization (checkerboard: one square = one quad)" : "input mesh", mesh.V(),
                         std::move(triangles), param ? param->uv : Eigen::MatrixX3cd(), false});
  if (quality && !quality->arap_per_face.empty()) {
    Histogram h;
    h.title = "ARAP energy per triangle";
    h.x_label = "1/2 min_R |J - R|^2";
    h.values = quality->arap_per_face;
    h.weights.assign(mesh.face_areas().data(), mesh.face_areas().data() + mesh.num_faces());
    h.y_label = "area";
    page.figures.emplace_back("Area-weighted histogram of the per-triangle ARAP energy (thesis Fig. 6.2)",
                              histogram_svg(h));
  }
  if (quads) {
    page.meshes.push_back({"quad mesh", quads->V, quads->faces, {}, true});
    for (auto& fig : polygon_mesh_figures(quads->V, quads->faces)) page.figures.push_back(std::move(fig));
  }
  write_html_report(path, page);
}

}  // namespace quadcover
