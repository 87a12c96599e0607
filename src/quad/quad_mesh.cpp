#include "quad/quad_mesh.h"

#include <algorithm>
#include <unordered_map>

namespace quadcover {

int QuadMesh::num_quads() const {
  return static_cast<int>(std::count_if(faces.begin(), faces.end(), [](const auto& f) { return f.size() == 4; }));
}

PolygonTopology polygon_topology(int num_vertices, const std::vector<std::vector<int>>& faces) {
  PolygonTopology t;
  t.faces = static_cast<int>(faces.size());
  // Directed edge (a,b) -> number of uses; the undirected edge is manifold iff each direction is used at most once.
  std::unordered_map<long long, int> directed;
  directed.reserve(faces.size() * 5);
  auto key = [](int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); };
  std::vector<int> uses(num_vertices, 0);
  for (const auto& f : faces) {
    const int n = static_cast<int>(f.size());
    bool degenerate = n < 3;
    for (int i = 0; i < n && !degenerate; ++i)
      for (int j = i + 1; j < n; ++j)
        if (f[i] == f[j]) degenerate = true;
    if (degenerate) ++t.degenerate_faces;
    for (int i = 0; i < n; ++i) {
      ++uses[f[i]];
      ++directed[key(f[i], f[(i + 1) % n])];
    }
  }
  for (const auto& [k, count] : directed) {
    const int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffff);
    const auto rev = directed.find(key(b, a));
    const int back = rev == directed.end() ? 0 : rev->second;
    if (a < b || back == 0) {  // count each undirected edge once
      ++t.edges;
      if (back == 0) ++t.boundary_edges;
      if (count > 1 || back > 1) ++t.non_manifold_edges;
    }
  }
  // Vertex manifoldness: the corners at v, linked by shared edges, must form a single chain or cycle (one fan).
  // Corner (face, i) at v has incoming edge (prev, v) and outgoing edge (v, next); the fan links corner c to the
  // corner whose incoming edge is the reverse of c's outgoing edge.
  std::vector<int> offset(num_vertices + 1, 0);
  for (int v = 0; v < num_vertices; ++v) offset[v + 1] = offset[v] + uses[v];
  std::vector<std::pair<int, int>> corner_edges(offset[num_vertices]);  // (prev vertex, next vertex)
  std::vector<int> fill(offset.begin(), offset.end() - 1);
  for (const auto& f : faces) {
    const int n = static_cast<int>(f.size());
    for (int i = 0; i < n; ++i) corner_edges[fill[f[i]]++] = {f[(i + n - 1) % n], f[(i + 1) % n]};
  }
  for (int v = 0; v < num_vertices; ++v) {
    if (uses[v] == 0) {
      ++t.isolated_vertices;
      continue;
    }
    ++t.vertices;
    // Union-find over the corners at v: corners sharing an edge neighbour are in the same fan.
    const int m = uses[v];
    std::vector<int> parent(m);
    for (int i = 0; i < m; ++i) parent[i] = i;
    auto find = [&](int i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    std::unordered_map<int, int> by_next;
    for (int i = 0; i < m; ++i) by_next.emplace(corner_edges[offset[v] + i].second, i);
    for (int i = 0; i < m; ++i) {
      const auto it = by_next.find(corner_edges[offset[v] + i].first);
      if (it != by_next.end()) parent[find(i)] = find(it->second);
    }
    int roots = 0;
    for (int i = 0; i < m; ++i) roots += find(i) == i;
    if (roots > 1) ++t.non_manifold_vertices;
  }
  t.euler_characteristic = t.vertices - t.edges + t.faces;
  return t;
}

}  // namespace quadcover
