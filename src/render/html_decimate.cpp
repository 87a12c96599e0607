#include "render/html_decimate.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

namespace quadcover {

namespace {

double surface_area(const HtmlMesh& m) {
  double area = 0;
  for (const auto& f : m.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      const Eigen::Vector3d a = m.V.row(f[0]), b = m.V.row(f[i]), c = m.V.row(f[i + 1]);
      area += 0.5 * (b - a).cross(c - a).norm();
    }
  return area;
}

/// Cell of every vertex (numbered in order of first vertex) and the mean position of each cell.
std::vector<int> cluster(const Eigen::MatrixX3d& V, double cell, Eigen::MatrixX3d& centres) {
  const Eigen::RowVector3d lo = V.colwise().minCoeff();
  std::map<std::array<long long, 3>, int> id;
  std::vector<int> of(static_cast<std::size_t>(V.rows()));
  std::vector<Eigen::RowVector3d> sum;
  std::vector<int> count;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    std::array<long long, 3> key{};
    for (int d = 0; d < 3; ++d) key[d] = static_cast<long long>(std::floor((V(v, d) - lo[d]) / cell));
    const auto [it, fresh] = id.emplace(key, static_cast<int>(sum.size()));
    if (fresh) {
      sum.emplace_back(Eigen::RowVector3d::Zero());
      count.push_back(0);
    }
    of[static_cast<std::size_t>(v)] = it->second;
    sum[static_cast<std::size_t>(it->second)] += V.row(v);
    ++count[static_cast<std::size_t>(it->second)];
  }
  centres.resize(static_cast<Eigen::Index>(sum.size()), 3);
  for (std::size_t c = 0; c < sum.size(); ++c) centres.row(static_cast<Eigen::Index>(c)) = sum[c] / count[c];
  return of;
}

/// The mesh on the cells: faces with repeated cells removed (kept if >= 3 remain, once per set of cells).
HtmlMesh clustered(const HtmlMesh& m, double cell) {
  HtmlMesh out;
  out.name = m.name;
  out.wireframe = m.wireframe;
  out.decimated_from = m.faces.size();
  out.cell_size = cell;
  const std::vector<int> of = cluster(m.V, cell, out.V);
  const bool with_uv = m.uv.rows() == static_cast<Eigen::Index>(m.faces.size());
  std::vector<Eigen::Index> kept_uv;
  std::set<std::vector<int>> seen;
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    std::vector<int> poly;
    for (int v : m.faces[f]) {
      const int c = of[static_cast<std::size_t>(v)];
      if (poly.empty() || poly.back() != c) poly.push_back(c);
    }
    while (poly.size() > 1 && poly.back() == poly.front()) poly.pop_back();
    std::vector<int> key = poly;
    std::sort(key.begin(), key.end());
    if (std::adjacent_find(key.begin(), key.end()) != key.end() || key.size() < 3 || !seen.insert(key).second) continue;
    out.faces.push_back(std::move(poly));
    kept_uv.push_back(static_cast<Eigen::Index>(f));
  }
  if (with_uv) {
    out.uv.resize(static_cast<Eigen::Index>(kept_uv.size()), 3);
    for (std::size_t i = 0; i < kept_uv.size(); ++i) out.uv.row(static_cast<Eigen::Index>(i)) = m.uv.row(kept_uv[i]);
  }
  std::set<std::pair<int, int>> seams;
  for (const auto& [a, b] : m.seams) {
    const int ca = of[static_cast<std::size_t>(a)], cb = of[static_cast<std::size_t>(b)];
    if (ca != cb) seams.insert({std::min(ca, cb), std::max(ca, cb)});
  }
  out.seams.assign(seams.begin(), seams.end());
  for (const BranchPoint& b : m.branch_points)
    out.branch_points.push_back({of[static_cast<std::size_t>(b.vertex)], b.quarter_index});
  return out;
}

}  // namespace

HtmlMesh decimate_display_mesh(const HtmlMesh& mesh, std::size_t max_faces) {
  if (mesh.faces.size() <= max_faces || mesh.V.rows() == 0) return mesh;
  // A closed triangle mesh has about F/2 vertices, a quad mesh about F: one cell per output vertex.
  double triangles = 0;
  for (const auto& f : mesh.faces) triangles += static_cast<double>(f.size()) - 2;
  const double vertices_per_face = triangles / static_cast<double>(mesh.faces.size()) > 1.5 ? 1.0 : 0.5;
  double cell = std::sqrt(surface_area(mesh) / (vertices_per_face * static_cast<double>(max_faces)));
  if (!(cell > 0)) cell = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm() / 100 + 1e-300;
  for (;;) {
    HtmlMesh out = clustered(mesh, cell);
    if (out.faces.size() <= max_faces) return out;
    cell *= 1.25;
  }
}

}  // namespace quadcover
