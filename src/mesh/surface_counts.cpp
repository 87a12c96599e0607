#include "mesh/surface_counts.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>

#include "common/errors.h"
#include "common/union_find.h"
#include "mesh/mesh.h"

namespace quadcover {

namespace {

using Sets = detail::UnionFind;  // corners, boundary edges, vertices

/// The faces' sides (corner c runs from its vertex to the next corner's) grouped into undirected edges.
struct Sides {
  std::vector<int> offset;              ///< #faces + 1: first corner of each face
  std::vector<int> vertex, next, prev;  ///< per corner: its vertex, the next / previous corner in its face
  std::vector<int> edge;                ///< per corner: the edge of its side, −1 for a side a → a
  std::vector<int> sides, forward;      ///< per edge: face sides on it, and how many run low → high
};

Sides collect_sides(const std::vector<std::vector<int>>& faces) {
  Sides s;
  s.offset.assign(faces.size() + 1, 0);
  for (std::size_t f = 0; f < faces.size(); ++f) s.offset[f + 1] = s.offset[f] + static_cast<int>(faces[f].size());
  const int corners = s.offset.back();
  s.vertex.resize(corners), s.next.resize(corners), s.prev.resize(corners), s.edge.assign(corners, -1);
  std::vector<std::pair<std::uint64_t, int>> keyed;  // (unordered edge, corner)
  keyed.reserve(corners);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const int n = static_cast<int>(faces[f].size()), o = s.offset[f];
    for (int i = 0; i < n; ++i) {
      s.vertex[o + i] = faces[f][i];
      s.next[o + i] = o + (i + 1) % n;
      s.prev[o + i] = o + (i + n - 1) % n;
      const auto a = static_cast<std::uint32_t>(faces[f][i]), b = static_cast<std::uint32_t>(faces[f][(i + 1) % n]);
      if (a != b) keyed.emplace_back((std::uint64_t{std::min(a, b)} << 32) | std::max(a, b), o + i);
    }
  }
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) s.sides.push_back(0), s.forward.push_back(0);
    const int c = keyed[i].second, e = static_cast<int>(s.sides.size()) - 1;
    s.edge[c] = e;
    ++s.sides[e];
    s.forward[e] += s.vertex[c] < s.vertex[s.next[c]];
  }
  return s;
}

/// Links the corners at each vertex into fans (through edges of exactly two sides) and the boundary edges into
/// loops (the two boundary edges of one fan at a vertex are consecutive in a loop). Counts non-manifold vertices.
void count_fans_and_loops(int num_vertices, const Sides& s, SurfaceCounts& c) {
  const int corners = static_cast<int>(s.vertex.size());
  std::vector<int> begin(static_cast<std::size_t>(num_vertices) + 1, 0), at(corners);
  for (int k = 0; k < corners; ++k) ++begin[s.vertex[k] + 1];
  for (int v = 0; v < num_vertices; ++v) begin[v + 1] += begin[v];
  {
    std::vector<int> fill(begin.begin(), begin.end() - 1);
    for (int k = 0; k < corners; ++k) at[fill[s.vertex[k]]++] = k;
  }
  std::vector<int> boundary_id(s.sides.size(), -1);
  int nb = 0;
  for (std::size_t e = 0; e < s.sides.size(); ++e)
    if (s.sides[e] == 1) boundary_id[e] = nb++;
  Sets fans(corners), loops(nb);
  std::vector<std::pair<int, int>> links;  // (edge or fan, corner or boundary edge) at one vertex
  for (int v = 0; v < num_vertices; ++v) {
    links.clear();
    for (int i = begin[v]; i < begin[v + 1]; ++i)
      for (const int e : {s.edge[at[i]], s.edge[s.prev[at[i]]]})
        if (e >= 0 && s.sides[e] == 2) links.emplace_back(e, at[i]);
    std::sort(links.begin(), links.end());
    for (std::size_t i = 1; i < links.size(); ++i)
      if (links[i].first == links[i - 1].first) fans.unite(links[i].second, links[i - 1].second);
    links.clear();
    int roots = 0;
    for (int i = begin[v]; i < begin[v + 1]; ++i) {
      roots += fans.find(at[i]) == at[i];
      for (const int e : {s.edge[at[i]], s.edge[s.prev[at[i]]]})
        if (e >= 0 && boundary_id[e] >= 0) links.emplace_back(fans.find(at[i]), boundary_id[e]);
    }
    c.non_manifold_vertices += roots > 1;
    std::sort(links.begin(), links.end());
    for (std::size_t i = 1; i < links.size(); ++i)
      if (links[i].first == links[i - 1].first) loops.unite(links[i].second, links[i - 1].second);
  }
  for (int b = 0; b < nb; ++b) c.boundary_loops += loops.find(b) == b;
}

}  // namespace

SurfaceCounts surface_counts(int num_vertices, const std::vector<std::vector<int>>& faces) {
  SurfaceCounts c;
  c.faces = static_cast<int>(faces.size());
  const Sides s = collect_sides(faces);
  c.edges = static_cast<int>(s.sides.size());
  for (std::size_t e = 0; e < s.sides.size(); ++e) {
    c.boundary_edges += s.sides[e] == 1;
    c.non_manifold_edges += s.sides[e] > 2;
    c.inconsistent_edges += s.sides[e] == 2 && s.forward[e] != 1;
  }
  Sets components(num_vertices);
  std::vector<char> used(static_cast<std::size_t>(num_vertices), 0);
  for (const auto& f : faces) {
    c.non_quads += f.size() != 4;
    std::vector<int> sorted(f);
    std::sort(sorted.begin(), sorted.end());
    c.degenerate_faces += f.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
    for (std::size_t i = 0; i < f.size(); ++i) {
      used[f[i]] = 1;
      components.unite(f[i], f[(i + 1) % f.size()]);
    }
  }
  for (int v = 0; v < num_vertices; ++v) {
    c.vertices += used[v];
    c.components += used[v] && components.find(v) == v;
  }
  c.isolated_vertices = num_vertices - c.vertices;
  count_fans_and_loops(num_vertices, s, c);
  c.euler_characteristic = c.vertices - c.edges + c.faces;
  if (c.manifold() && c.oriented()) c.genus = (2 * c.components - c.euler_characteristic - c.boundary_loops) / 2;
  return c;
}

SurfaceCounts surface_counts(const Mesh& mesh) {
  std::vector<std::vector<int>> faces(static_cast<std::size_t>(mesh.num_faces()));
  for (int f = 0; f < mesh.num_faces(); ++f) faces[f] = {mesh.F()(f, 0), mesh.F()(f, 1), mesh.F()(f, 2)};
  return surface_counts(mesh.num_vertices(), faces);
}

std::vector<std::vector<int>> soup_polygons(const PolygonSoup& soup) {
  const auto nv = static_cast<std::int64_t>(soup.num_vertices());
  std::vector<std::vector<int>> faces(soup.num_faces());
  for (std::size_t f = 0; f < soup.num_faces(); ++f)
    for (std::size_t j = 0; j < soup.face_size(f); ++j) {
      const std::int64_t v = soup.face_begin(f)[j];
      if (v < 0 || v >= nv)
        throw InputError(soup.file, f < soup.face_lines.size() ? soup.face_lines[f] : 0,
                         "vertex index " + std::to_string(v + soup.index_base) + " out of range");
      faces[f].push_back(static_cast<int>(v));
    }
  return faces;
}

nlohmann::json to_json(const SurfaceCounts& c) {
  return {{"vertices", c.vertices},
          {"edges", c.edges},
          {"faces", c.faces},
          {"components", c.components},
          {"boundary_loops", c.boundary_loops},
          {"euler_characteristic", c.euler_characteristic},
          {"genus", c.genus >= 0 ? nlohmann::json(c.genus) : nlohmann::json(nullptr)},
          {"manifold", c.manifold()},
          {"oriented", c.oriented()},
          {"closed", c.closed()},
          {"boundary_edges", c.boundary_edges},
          {"non_manifold_edges", c.non_manifold_edges},
          {"non_manifold_vertices", c.non_manifold_vertices},
          {"inconsistent_edges", c.inconsistent_edges},
          {"degenerate_faces", c.degenerate_faces},
          {"isolated_vertices", c.isolated_vertices},
          {"non_quads", c.non_quads}};
}

}  // namespace quadcover
