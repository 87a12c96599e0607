// Doublet removal (see doublets.h).
#include "quad/doublets.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <vector>

#include "mesh/triangle_tree.h"

namespace quadcover {

namespace {

/// f's corners rotated to start at v. \pre v is a corner of f.
std::vector<int> starting_at(const std::vector<int>& f, int v) {
  std::vector<int> out(f);
  std::rotate(out.begin(), std::find(out.begin(), out.end(), v), out.end());
  return out;
}

/// The faces around each vertex, each face once.
struct VertexFaces {
  std::vector<std::vector<int>> of;
  explicit VertexFaces(const QuadMesh& q) : of(static_cast<std::size_t>(q.num_vertices())) {
    for (int f = 0; f < q.num_faces(); ++f)
      for (int v : q.faces[f])
        if (std::find(of[v].begin(), of[v].end(), f) == of[v].end()) of[v].push_back(f);
  }
  /// Face `gone` merged into `kept`: its corners' lists name `kept` instead.
  void merge(const std::vector<int>& gone_corners, int gone, int kept) {
    for (int v : gone_corners) {
      auto& list = of[v];
      list.erase(std::remove(list.begin(), list.end(), gone), list.end());
      if (std::find(list.begin(), list.end(), kept) == list.end()) list.push_back(kept);
    }
  }
};

/// The union of faces A and B around their doublet vertex v (A = v, q, …, p and B = v, p, …, q): A from q round to
/// p, then B's corners strictly between p and q; then every fold x → y → x whose middle y no third face uses is
/// removed with y (a chain of doublet vertices). Nothing when v is no doublet of A and B (they do not share both
/// edges at v) or the union is not a simple polygon of at least three corners. `removed` receives the vertices that
/// go (v first).
std::optional<std::vector<int>> merged_polygon(const std::vector<int>& A, const std::vector<int>& B, int v,
                                               const VertexFaces& around, std::vector<int>& removed) {
  const std::vector<int> a = starting_at(A, v), b = starting_at(B, v);
  if (a.size() < 3 || b.size() < 3 || b[1] != a.back() || b.back() != a[1]) return std::nullopt;
  std::vector<int> poly(a.begin() + 1, a.end());
  poly.insert(poly.end(), b.begin() + 2, b.end() - 1);
  removed.assign(1, v);
  for (bool folded = true; folded && poly.size() >= 3;) {
    folded = false;
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i) {
      const int prev = poly[(i + n - 1) % n], mid = poly[i], next = poly[(i + 1) % n];
      if (prev != next || around.of[mid].size() != 2) continue;
      removed.push_back(mid);
      const std::size_t j = (i + 1) % n;  // drop mid and one copy of its neighbour
      poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(std::max(i, j)));
      poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(std::min(i, j)));
      folded = true;
      break;
    }
  }
  std::vector<int> sorted = poly;
  std::sort(sorted.begin(), sorted.end());
  if (poly.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return std::nullopt;
  return poly;
}

/// Whether every removed vertex lies within max_offset × (the polygon's mean side) of the polygon (fanned from its
/// centroid): the merged face still covers the surface the removed vertices held (not a tip cut off).
bool covers_removed(const QuadMesh& q, const std::vector<int>& poly, const std::vector<int>& removed,
                    double max_offset) {
  const std::size_t n = poly.size();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double side = 0;
  for (std::size_t i = 0; i < n; ++i) {
    centre += q.V.row(poly[i]).transpose() / static_cast<double>(n);
    side += (q.V.row(poly[i]) - q.V.row(poly[(i + 1) % n])).norm() / static_cast<double>(n);
  }
  for (int r : removed) {
    const Eigen::Vector3d x = q.V.row(r).transpose();
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i)
      d = std::min(d, (x - closest_point_on_triangle(x, centre, q.V.row(poly[i]).transpose(),
                                                     q.V.row(poly[(i + 1) % n]).transpose()))
                          .norm());
    if (d > max_offset * side) return false;
  }
  return true;
}

}  // namespace

int remove_doublets(QuadMesh& q, double max_offset) {
  VertexFaces around(q);
  const std::vector<char> on_boundary = quad_boundary_vertices(q);  // merging inside never changes the boundary
  int removed_vertices = 0;
  std::vector<int> removed;
  for (bool changed = true; changed;) {
    changed = false;
    for (int v = 0; v < q.num_vertices(); ++v) {
      if (around.of[v].size() != 2 || on_boundary[v]) continue;
      const int f = std::min(around.of[v][0], around.of[v][1]), g = std::max(around.of[v][0], around.of[v][1]);
      const std::optional<std::vector<int>> poly = merged_polygon(q.faces[f], q.faces[g], v, around, removed);
      const bool adds_non_quad = q.faces[f].size() == 4 && q.faces[g].size() == 4 && poly && poly->size() != 4;
      if (!poly || adds_non_quad || !covers_removed(q, *poly, removed, max_offset)) continue;
      around.merge(q.faces[g], g, f);
      for (int r : removed) around.of[r].clear();
      q.faces[f] = *poly;
      q.faces[g].clear();
      removed_vertices += static_cast<int>(removed.size());
      changed = true;
    }
  }
  q.faces.erase(std::remove_if(q.faces.begin(), q.faces.end(), [](const auto& f) { return f.empty(); }), q.faces.end());
  return removed_vertices;
}

}  // namespace quadcover
