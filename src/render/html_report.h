#pragma once
// A self-contained HTML report: the metrics table (from a JSON report), plots as inline SVG, and interactive 3D
// views of the textured mesh and the quad mesh (three.js bundled into the page: it opens from disk, offline).
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "field/frame_field.h"
#include "render/plots.h"

namespace quadcover {

/// A mesh for an interactive view: triangles with optional per-corner UVs (checkerboard) or polygons (wireframe).
struct HtmlMesh {
  std::string name;
  Eigen::MatrixX3d V;                   ///< #V by 3
  std::vector<std::vector<int>> faces;  ///< polygons (triangles for a parameterized mesh)
  Eigen::MatrixX3cd uv;                 ///< #faces by 3 per-corner u + iv (triangles only), or empty
  bool wireframe = false;               ///< draw every face edge
  /// Seam edges (vertex pairs) and branch points drawn over the surface; for a mesh with uv, html_report() finds
  /// them from the coordinates (render_mesh.h uv_seam_edges, cones_from_uv) when both are empty.
  std::vector<std::pair<int, int>> seams{};
  std::vector<BranchPoint> branch_points{};
  std::size_t decimated_from = 0;  ///< face count before decimate_display_mesh (0: the full mesh)
  double cell_size = 0;            ///< its clustering cell, model units
};

struct HtmlReport {
  std::string title = "quadcover report";
  nlohmann::json metrics;  ///< shown as a table (nested objects flattened to "a.b" keys), embedded whole as data.report
  std::vector<std::pair<std::string, std::string>> figures;  ///< (caption, inline SVG)
  std::vector<HtmlMesh> meshes;
  /// Meshes with more faces are shown decimated (html_decimate.h), and the page says so: about 5 MB at most for
  /// two views (a display triangle with per-corner uv costs ~60 bytes, a wireframe quad ~70).
  std::size_t max_display_faces = 30000;
};

/// Figures of a param / remesh report: its "optimize": {"log": [{"evaluation", "E_D", "branch_points", ...}]} ->
/// E_D and the branch point count over the evaluations (thesis Fig. 6.1); none without an optimization log.
/// \pre none (an absent or malformed log gives no figure).
std::vector<std::pair<std::string, std::string>> figures_from_report(const nlohmann::json& report);

/// Thesis Fig. 6.1: E_D (left axis) and the branch point count (right axis) over the iterations, from rows with
/// "iteration" (or "evaluation", as in the optimize log), "E_D" and "branch_points". \pre none
LinePlot optimization_history_plot(const nlohmann::json& history);

/// Edge-length and corner-angle (degrees) histograms of a polygon mesh (Fig. 7.1 style), as (caption, SVG).
/// \pre every face index is a row of V.
std::vector<std::pair<std::string, std::string>> polygon_mesh_figures(const Eigen::MatrixX3d& V,
                                                                      const std::vector<std::vector<int>>& faces);

/// The key numbers of a param / remesh report (as the CLI's summary line), in page order: (label, value); entries
/// absent from the report are left out. \pre none
std::vector<std::pair<std::string, std::string>> key_numbers(const nlohmann::json& report);

/// The page as one string (UTF-8): title, key numbers, the 3D views (with seams and branch points), plots, then
/// the whole metric table. \pre none
std::string html_report(const HtmlReport& report);
/// Writes the page atomically. \throw InputError naming the path on failure.
void write_html_report(const std::string& path, const HtmlReport& report);

}  // namespace quadcover
