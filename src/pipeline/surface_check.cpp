#include "pipeline/surface_check.h"

#include <map>
#include <utility>

#include "quad/quad_mesh.h"
#include "topology/union_find.h"

namespace quadcover {

namespace {

/// Boundary loops of the directed boundary edges (edges whose reverse no face uses): each loop is a cycle when the
/// mesh is manifold; at a pinched vertex the loops through it are counted by following the first unused edge.
int count_boundary_loops(const std::vector<std::vector<int>>& faces) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& f : faces)
    for (std::size_t i = 0; i < f.size(); ++i) ++directed[{f[i], f[(i + 1) % f.size()]}];
  std::multimap<int, int> next;  // boundary edge a → b, listed by a
  for (const auto& [e, count] : directed)
    if (!directed.count({e.second, e.first})) next.emplace(e.first, e.second);
  int loops = 0;
  while (!next.empty()) {
    auto it = next.begin();
    const int start = it->first;
    int v = it->second;
    next.erase(it);
    for (auto step = next.find(v); v != start && step != next.end(); step = next.find(v)) {
      v = step->second;
      next.erase(step);
    }
    ++loops;
  }
  return loops;
}

}  // namespace

SurfaceCounts surface_counts(int num_vertices, const std::vector<std::vector<int>>& faces) {
  SurfaceCounts c;
  const PolygonTopology t = polygon_topology(num_vertices, faces);
  c.euler_characteristic = t.euler_characteristic;
  c.non_manifold_edges = t.non_manifold_edges;
  c.non_manifold_vertices = t.non_manifold_vertices;
  detail::UnionFind sets(num_vertices);
  std::vector<char> used(static_cast<std::size_t>(num_vertices), 0);
  for (const auto& f : faces) {
    c.non_quads += f.size() != 4;
    for (std::size_t i = 0; i < f.size(); ++i) {
      used[static_cast<std::size_t>(f[i])] = 1;
      sets.unite(f[i], f[(i + 1) % f.size()]);
    }
  }
  for (int v = 0; v < num_vertices; ++v) c.components += used[static_cast<std::size_t>(v)] && sets.find(v) == v;
  c.boundary_loops = count_boundary_loops(faces);
  return c;
}

SurfaceCounts surface_counts(const Mesh& mesh) {
  SurfaceCounts c;
  c.components = mesh.num_components();
  c.boundary_loops = mesh.num_boundary_loops();
  c.euler_characteristic = mesh.euler_characteristic();
  return c;
}

SurfaceCheck check_surface(const Mesh& input, int num_vertices, const std::vector<std::vector<int>>& faces) {
  SurfaceCheck s;
  s.input = surface_counts(input);
  s.output = surface_counts(num_vertices, faces);
  const SurfaceCounts &a = s.input, &b = s.output;
  auto differ = [&](const char* what, int x, int y) {
    if (x != y)
      s.problems.push_back(std::string(what) + ": " + std::to_string(y) + " in the quad mesh, " + std::to_string(x) +
                           " in the input");
  };
  differ("components", a.components, b.components);
  differ("boundary loops", a.boundary_loops, b.boundary_loops);
  differ("Euler characteristic", a.euler_characteristic, b.euler_characteristic);
  if (b.non_manifold_edges + b.non_manifold_vertices > 0)
    s.problems.push_back("the quad mesh is not manifold (" + std::to_string(b.non_manifold_edges) + " edges, " +
                         std::to_string(b.non_manifold_vertices) + " vertices)");
  s.same_topology = s.problems.empty();
  const bool closed = a.boundary_loops == 0;
  s.closed_all_quads = !closed || (b.boundary_loops == 0 && b.non_quads == 0 && s.same_topology);
  if (closed && b.non_quads > 0)
    s.problems.push_back("the input is closed but " + std::to_string(b.non_quads) + " faces are not quads");
  return s;
}

nlohmann::json to_json(const SurfaceCheck& s) {
  auto counts = [](const SurfaceCounts& c) {
    return nlohmann::json{{"components", c.components},
                          {"boundary_loops", c.boundary_loops},
                          {"euler_characteristic", c.euler_characteristic},
                          {"non_manifold_edges", c.non_manifold_edges},
                          {"non_manifold_vertices", c.non_manifold_vertices},
                          {"non_quads", c.non_quads}};
  };
  return {{"input", counts(s.input)},
          {"output", counts(s.output)},
          {"same_topology", s.same_topology},
          {"closed_all_quads", s.closed_all_quads},
          {"problems", s.problems}};
}

}  // namespace quadcover
