#include "render/render_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <unordered_map>

namespace quadcover {

namespace {

Rgb scale(Rgb a, double s) { return {a.r * s, a.g * s, a.b * s}; }
Rgb add(Rgb a, double s) { return {a.r + s, a.g + s, a.b + s}; }

double uv_extent(const Eigen::MatrixX3cd& uv) {
  double lo_u = 1e300, hi_u = -1e300, lo_v = 1e300, hi_v = -1e300;
  for (Eigen::Index i = 0; i < uv.size(); ++i) {
    const std::complex<double> z = uv.data()[i];
    lo_u = std::min(lo_u, z.real());
    hi_u = std::max(hi_u, z.real());
    lo_v = std::min(lo_v, z.imag());
    hi_v = std::max(hi_v, z.imag());
  }
  return uv.size() ? std::max(hi_u - lo_u, hi_v - lo_v) : 0.0;
}

// Directed edge (a, b) -> (face, edge k); interior edges are found as the pair (a, b) / (b, a).
struct HalfEdges {
  std::unordered_map<long long, std::pair<int, int>> map;
  static long long key(int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); }
  explicit HalfEdges(const Eigen::MatrixX3i& F) {
    map.reserve(static_cast<std::size_t>(F.rows()) * 3);
    for (int f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k) map[key(F(f, (k + 1) % 3), F(f, (k + 2) % 3))] = {f, k};
  }
};

// Shading of a surface point with unit normal n: Lambert + Blinn from a key light (unit, towards the light), two-sided.
struct Lighting {
  Eigen::Vector3d view, light, half;
  explicit Lighting(const Projection& p)
      : view(p.toward_viewer()), light(p.toward_light()), half((view + light).normalized()) {}
  Rgb operator()(Rgb base, Eigen::Vector3d n) const {
    double tint = 1.0;
    if (n.dot(view) < 0) {  // back face (seen through a hole): shade as two-sided, darker
      n = -n;
      tint = 0.6;
    }
    const double diffuse = 0.28 + 0.67 * std::max(0.0, n.dot(light));
    const double specular = 0.15 * std::pow(std::max(0.0, n.dot(half)), 40.0);
    return add(scale(base, diffuse * tint), specular * tint);
  }
};

Eigen::MatrixX3d vertex_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(V.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);  // area-weighted
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n.transpose();
  }
  for (Eigen::Index v = 0; v < N.rows(); ++v) {
    const double len = N.row(v).norm();
    if (len > 0) N.row(v) /= len;
  }
  return N;
}

}  // namespace

Rgb branch_point_color(int quarter_index) {
  switch (quarter_index) {
    case 1:
      return {0.10, 0.25, 0.95};
    case -1:
      return {0.92, 0.10, 0.10};
    case 2:
      return {0.0, 0.75, 0.80};
    case -2:
      return {0.85, 0.10, 0.80};
    default:
      return {0.25, 0.25, 0.25};
  }
}

std::vector<std::pair<int, int>> uv_seam_edges(const Eigen::MatrixX3i& F, const Eigen::MatrixX3cd& uv,
                                               double tolerance) {
  std::vector<std::pair<int, int>> seams;
  if (uv.rows() != F.rows()) return seams;
  const double tol = tolerance * std::max(uv_extent(uv), 1e-300);
  const HalfEdges half(F);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, (k + 1) % 3), b = F(f, (k + 2) % 3);
      const auto it = half.map.find(HalfEdges::key(b, a));
      if (it == half.map.end()) continue;  // boundary
      const auto [g, l] = it->second;
      if (g < f) continue;  // each interior edge once
      // In g the edge runs b -> a: corner l+1 is b, l+2 is a.
      const double jump = std::max(std::abs(uv(f, (k + 1) % 3) - uv(g, (l + 2) % 3)),
                                   std::abs(uv(f, (k + 2) % 3) - uv(g, (l + 1) % 3)));
      if (jump > tol) seams.emplace_back(f, k);
    }
  return seams;
}

Image render_textured_mesh(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, const Eigen::MatrixX3cd& uv,
                           const std::vector<BranchPoint>& branch_points, const RenderOptions& o) {
  Canvas canvas(o.width, o.height, o.supersample, o.background);
  const Projection project(o.camera, V, o.width, o.height);
  const Lighting shade(project);
  const Eigen::MatrixX3d N = vertex_normals(V, F);
  const bool textured = uv.rows() == F.rows() && o.texture != SurfaceTexture::None;
  const double period = o.texture_period > 0 ? o.texture_period : 1.0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p[3] = {project(V.row(F(f, 0))), project(V.row(F(f, 1))), project(V.row(F(f, 2)))};
    const Eigen::Vector3d n[3] = {N.row(F(f, 0)), N.row(F(f, 1)), N.row(F(f, 2))};
    // UV units per output pixel on this triangle (for grid lines of constant on-screen width).
    double uv_per_pixel = 0;
    if (textured && o.texture == SurfaceTexture::GridLines) {
      const double screen = std::abs((p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x());
      const double param = std::abs(std::imag(std::conj(uv(f, 1) - uv(f, 0)) * (uv(f, 2) - uv(f, 0))));
      uv_per_pixel = screen > 0 ? std::sqrt(param / screen) : 0;
    }
    canvas.fill_triangle(p[0], p[1], p[2], [&](const Eigen::Vector3d& b) {
      Rgb base = o.color_light;
      if (textured) {
        const std::complex<double> z = (b[0] * uv(f, 0) + b[1] * uv(f, 1) + b[2] * uv(f, 2)) / period;
        if (o.texture == SurfaceTexture::Checkerboard) {
          const long long parity =
              static_cast<long long>(std::floor(z.real())) + static_cast<long long>(std::floor(z.imag()));
          if (parity & 1) base = o.color_dark;
        } else {
          const double du = std::abs(z.real() - std::round(z.real())), dv = std::abs(z.imag() - std::round(z.imag()));
          const double half = 0.5 * o.line_width * uv_per_pixel / period;
          if (std::min(du, dv) < half) base = o.color_dark;
        }
      }
      const Eigen::Vector3d normal = (b[0] * n[0] + b[1] * n[1] + b[2] * n[2]).normalized();
      return shade(base, normal);
    });
  }
  const double offset = 0.006 * project.depth_range();
  if (o.show_seams && uv.rows() == F.rows())
    for (const auto& [f, k] : uv_seam_edges(F, uv))
      canvas.draw_line(project(V.row(F(f, (k + 1) % 3))), project(V.row(F(f, (k + 2) % 3))), o.line_width * 1.3,
                       o.seam_color, offset);
  if (o.show_branch_points)
    for (const BranchPoint& bp : branch_points)
      if (bp.vertex >= 0 && bp.vertex < V.rows())
        canvas.draw_disk(project(V.row(bp.vertex)), o.point_radius, branch_point_color(bp.quarter_index), 2 * offset);
  return canvas.resolve();
}

Image render_polygon_mesh(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces,
                          const RenderOptions& o) {
  Canvas canvas(o.width, o.height, o.supersample, o.background);
  const Projection project(o.camera, V, o.width, o.height);
  const Lighting shade(project);
  for (const auto& face : faces) {
    if (face.size() < 3) continue;
    // Newell normal of the polygon.
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < face.size(); ++i)
      n += Eigen::Vector3d(V.row(face[i])).cross(Eigen::Vector3d(V.row(face[(i + 1) % face.size()])));
    if (n.norm() > 0) n.normalize();
    const Rgb color = shade(o.color_light, n);
    const Eigen::Vector3d p0 = project(V.row(face[0]));
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
      canvas.fill_triangle(p0, project(V.row(face[i])), project(V.row(face[i + 1])),
                           [color](const Eigen::Vector3d&) { return color; });
  }
  const double offset = 0.004 * project.depth_range();
  for (const auto& face : faces)
    for (std::size_t i = 0; i < face.size(); ++i) {
      const int a = face[i], b = face[(i + 1) % face.size()];
      if (a < b || face.size() < 3)  // interior edges are shared: draw from one side (boundary ones may repeat)
        canvas.draw_line(project(V.row(a)), project(V.row(b)), o.line_width, o.wire_color, offset);
      else
        canvas.draw_line(project(V.row(b)), project(V.row(a)), o.line_width, o.wire_color, offset);
    }
  return canvas.resolve();
}

Image render_uv_layout(const Eigen::MatrixX3cd& uv, const FlipReport& flips, const UvLayoutOptions& o) {
  Canvas canvas(o.width, o.height, o.supersample, o.background);
  if (uv.rows() == 0) return canvas.resolve();
  double lo_u = 1e300, hi_u = -1e300, lo_v = 1e300, hi_v = -1e300;
  for (Eigen::Index i = 0; i < uv.size(); ++i) {
    lo_u = std::min(lo_u, uv.data()[i].real());
    hi_u = std::max(hi_u, uv.data()[i].real());
    lo_v = std::min(lo_v, uv.data()[i].imag());
    hi_v = std::max(hi_v, uv.data()[i].imag());
  }
  // Fit the layout's bounding box into the image with the margin on every side, keeping the aspect ratio.
  const double s = std::min(o.width * (1 - 2 * o.margin) / std::max(hi_u - lo_u, 1e-300),
                            o.height * (1 - 2 * o.margin) / std::max(hi_v - lo_v, 1e-300));
  const double cu = (lo_u + hi_u) / 2, cv = (lo_v + hi_v) / 2;
  const auto to_screen = [&](std::complex<double> z) {
    return Eigen::Vector3d(o.width / 2.0 + s * (z.real() - cu), o.height / 2.0 - s * (z.imag() - cv), 0);
  };
  // Integer grid behind the layout (depth 1 so triangles, at depth 0, cover it).
  if (o.integer_grid && s >= 4) {
    const auto line = [&](std::complex<double> a, std::complex<double> b) {
      Eigen::Vector3d pa = to_screen(a), pb = to_screen(b);
      pa.z() = pb.z() = 1;
      canvas.draw_line(pa, pb, 1.0, o.grid_color);
    };
    for (double u = std::ceil(lo_u); u <= hi_u; ++u) line({u, lo_v}, {u, hi_v});
    for (double v = std::ceil(lo_v); v <= hi_v; ++v) line({lo_u, v}, {hi_u, v});
  }
  // Non-positive triangles are drawn last (in front) so that a fold is never hidden by the sheet it covers.
  std::vector<char> bad(static_cast<std::size_t>(uv.rows()), 0);
  for (const int f : flips.flipped_faces) bad[static_cast<std::size_t>(f)] = 1;
  for (int pass = 0; pass < 2; ++pass)
    for (Eigen::Index f = 0; f < uv.rows(); ++f) {
      const bool flipped = bad[static_cast<std::size_t>(f)] != 0;
      if (flipped != (pass == 1)) continue;
      Eigen::Vector3d p[3];
      for (int k = 0; k < 3; ++k) {
        p[k] = to_screen(uv(f, k));
        p[k].z() = flipped ? -1 : 0;
      }
      const Rgb c = flipped ? o.flipped : o.fill;
      canvas.fill_triangle(p[0], p[1], p[2], [c](const Eigen::Vector3d&) { return c; });
      if (o.edges && s * std::sqrt(std::abs(std::imag(std::conj(uv(f, 1) - uv(f, 0)) * (uv(f, 2) - uv(f, 0))))) >= 3)
        for (int k = 0; k < 3; ++k) {
          Eigen::Vector3d a = p[k], b = p[(k + 1) % 3];
          canvas.draw_line(a, b, 0.6, flipped ? scale(o.flipped, 0.6) : o.edge_color, 0.5);
        }
      if (flipped)  // also a dot: a collapsed triangle covers no pixel
        canvas.draw_disk((p[0] + p[1] + p[2]) / 3, o.marker_radius, o.flipped, 2);
    }
  return canvas.resolve();
}

}  // namespace quadcover
