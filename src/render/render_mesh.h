#pragma once
// Pictures of meshes and parameterizations, rendered offscreen (no display, no GPU): a surface with a checkerboard
// or grid texture from per-corner UVs with seams and branch points marked, a polygon (quad) mesh as wireframe over
// shading, and the parameter domain (UV layout) with flipped triangles in red.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "field/frame_field.h"
#include "metrics/param_quality.h"
#include "param/seams.h"
#include "render/canvas.h"
#include "render/image.h"

namespace quadcover {

enum class SurfaceTexture { None, Checkerboard, GridLines };

/// Options of render_textured_mesh / render_polygon_mesh. Defaults give an 800×800 front view, 3×3 supersampling.
struct RenderOptions {
  int width = 800, height = 800;  ///< output pixels
  int supersample = 3;            ///< antialiasing: n×n samples per pixel (1 = none)
  ViewCamera camera;              ///< default: front
  SurfaceTexture texture = SurfaceTexture::Checkerboard;
  double texture_period = 1.0;     ///< UV units per checker square / grid cell (grid units: one quad)
  bool show_seams = true;          ///< draw edges where the UVs jump
  bool show_branch_points = true;  ///< dots at branch points (coloured by index)
  double line_width = 1.5;         ///< seams and wireframe, output pixels
  double point_radius = 4.0;       ///< branch point dots, output pixels
  Rgb background{1, 1, 1};
  Rgb color_light{0.93, 0.93, 0.90};  ///< checker light squares / base colour
  Rgb color_dark{0.35, 0.55, 0.80};   ///< checker dark squares / grid lines
  Rgb seam_color{0.90, 0.45, 0.05};
  Rgb wire_color{0.10, 0.10, 0.12};
};

/// Colour of a branch point dot by its quarter index 4·ind_p (Def. 3.2): +1 blue, -1 red, +2 cyan, -2 magenta,
/// other values dark grey. \pre none
Rgb branch_point_color(int quarter_index);

/// Face edges (f, k) (edge opposite corner k of f) of interior edges across which the per-corner UVs jump: the two
/// faces' coordinates differ at a shared endpoint by more than tolerance × (UV extent). Each such edge once.
/// F #F by 3; uv #F by 3 per-corner complex coordinates. \pre uv is #F by 3 or empty.
std::vector<std::pair<int, int>> uv_seam_edges(const Eigen::MatrixX3i& F, const Eigen::MatrixX3cd& uv,
                                               double tolerance = 1e-9);

// Cones of a map from its UVs: cones_from_uv (metrics/param_quality.h), the computation the reports use.

/// The triangle mesh shaded (Lambert + Blinn, headlight), textured from uv (may be empty: plain shading), with
/// seams and the given branch points marked.
/// V #V by 3; F #F by 3; uv #F by 3 or empty. \pre F indices are rows of V; uv #F by 3 or empty.
Image render_textured_mesh(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3cd& uv,
                           const std::vector<BranchPoint>& branch_points, const RenderOptions& options = {});

/// A polygon mesh (e.g. a quad mesh) with flat shading and its edges drawn as a wireframe.
/// V #V by 3; faces: 0-based vertex indices per polygon (3 or more). \pre face indices are rows of V.
Image render_polygon_mesh(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces,
                          const RenderOptions& options = {});

/// Options of render_uv_layout.
struct UvLayoutOptions {
  int width = 800, height = 800;
  int supersample = 3;
  double margin = 0.05;      ///< fraction of the image side left free around the layout
  bool integer_grid = true;  ///< light lines at integer coordinates (when at least 4 px apart)
  bool edges = true;         ///< triangle edges
  Rgb background{1, 1, 1};
  Rgb fill{0.78, 0.86, 0.95};     ///< positively oriented triangles
  Rgb flipped{0.90, 0.05, 0.05};  ///< flipped and collapsed triangles (FlipReport::flipped_faces)
  double marker_radius = 2.5;     ///< each non-positive triangle is also marked by a dot (px): collapsed ones are thin
  Rgb edge_color{0.25, 0.30, 0.40};
  Rgb grid_color{0.80, 0.80, 0.80};
};

/// The parameter domain: every triangle drawn at its per-corner UVs (u right, v up); the non-positive ones of
/// `flips` (flipped_triangles in param/seams.h: flipped or collapsed against τ·A_ref, the classification every report
/// uses) in red, in front, each also marked by a dot at its centroid (a collapsed one covers no pixel).
/// uv #F by 3 per-corner coordinates; flips.flipped_faces index its rows. \pre flips was measured on uv.
Image render_uv_layout(const Eigen::MatrixX3cd& uv, const FlipReport& flips, const UvLayoutOptions& options = {});

}  // namespace quadcover
