#pragma once
// An independent combinatorial check of a polygon mesh for the quad tests (written against the definitions, not
// against quad/quad_mesh.cpp): directed edges used once, undirected edges in at most two faces, one fan per vertex
// (corners linked through any shared neighbour), no vertex used by no face; boundary loops and components.
#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

namespace quadcover::testing {

struct PolygonCheck {
  int problems = 0;            ///< manifoldness violations of any kind
  int unreferenced = 0;        ///< vertices in no face
  int vertices = 0, edges = 0, faces = 0, boundary_edges = 0, boundary_loops = 0, components = 0;
  int euler() const { return vertices - edges + faces; }
};

inline PolygonCheck check_polygons(int nv, const std::vector<std::vector<int>>& faces) {
  PolygonCheck c;
  c.faces = static_cast<int>(faces.size());
  std::map<std::pair<int, int>, int> directed;
  std::map<std::pair<int, int>, std::vector<int>> undirected;
  std::vector<std::vector<std::pair<int, int>>> corners(nv);  // (prev, next) per corner at v
  for (int fi = 0; fi < c.faces; ++fi) {
    const auto& f = faces[fi];
    const int n = static_cast<int>(f.size());
    if (n < 3 || std::set<int>(f.begin(), f.end()).size() != f.size()) ++c.problems;
    for (int j = 0; j < n; ++j) {
      const int a = f[j], b = f[(j + 1) % n];
      if (directed[{a, b}]++ > 0) ++c.problems;
      undirected[{std::min(a, b), std::max(a, b)}].push_back(fi);
      corners[b].emplace_back(a, f[(j + 2) % n]);
    }
  }
  c.edges = static_cast<int>(undirected.size());
  std::vector<int> parent(c.faces);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<int, int> boundary_next;  // boundary half-edge a -> b (the face side's direction)
  for (const auto& [e, fs] : undirected) {
    if (fs.size() > 2) ++c.problems;
    if (fs.size() == 1) {
      ++c.boundary_edges;
      const bool forward = directed.count(e) > 0;
      boundary_next[forward ? e.first : e.second] = forward ? e.second : e.first;
    }
    for (std::size_t k = 1; k < fs.size(); ++k) parent[root(fs[k])] = root(fs[0]);
  }
  for (int i = 0; i < c.faces; ++i) c.components += root(i) == i;
  // Boundary loops: follow a -> b; a vertex with two boundary passes is a problem already (two fans).
  std::set<int> seen;
  for (const auto& [a, b] : boundary_next) {
    if (seen.count(a)) continue;
    ++c.boundary_loops;
    for (int v = a; !seen.count(v) && boundary_next.count(v); v = boundary_next[v]) seen.insert(v);
  }
  for (int v = 0; v < nv; ++v) {
    const auto& cs = corners[v];
    if (cs.empty()) {
      ++c.unreferenced;
      continue;
    }
    ++c.vertices;
    std::vector<int> fan(cs.size());
    std::iota(fan.begin(), fan.end(), 0);
    auto froot = [&](int i) {
      while (fan[i] != i) i = fan[i] = fan[fan[i]];
      return i;
    };
    std::map<int, int> by_neighbour;
    for (int i = 0; i < static_cast<int>(cs.size()); ++i)
      for (int x : {cs[i].first, cs[i].second}) {
        const auto [it, fresh] = by_neighbour.emplace(x, i);
        if (!fresh) fan[froot(i)] = froot(it->second);
      }
    int fans = 0;
    for (int i = 0; i < static_cast<int>(cs.size()); ++i) fans += froot(i) == i;
    if (fans > 1) ++c.problems;
  }
  return c;
}

/// The faces grouped by connected component (through shared undirected edges), in order of first face.
inline std::vector<std::vector<std::vector<int>>> split_components(const std::vector<std::vector<int>>& faces) {
  const int nf = static_cast<int>(faces.size());
  std::vector<int> parent(nf);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::pair<int, int>, int> first;
  for (int f = 0; f < nf; ++f)
    for (std::size_t j = 0; j < faces[f].size(); ++j) {
      const int a = faces[f][j], b = faces[f][(j + 1) % faces[f].size()];
      const auto [it, fresh] = first.emplace(std::pair{std::min(a, b), std::max(a, b)}, f);
      if (!fresh) parent[root(f)] = root(it->second);
    }
  std::map<int, int> index;
  std::vector<std::vector<std::vector<int>>> out;
  for (int f = 0; f < nf; ++f) {
    const auto [it, fresh] = index.emplace(root(f), static_cast<int>(out.size()));
    if (fresh) out.emplace_back();
    out[it->second].push_back(faces[f]);
  }
  return out;
}

}  // namespace quadcover::testing
