#include "topology/homology.h"

#include <algorithm>
#include <numeric>
#include <string>

#include "common/errors.h"
#include "common/union_find.h"

namespace quadcover {
namespace {

// A walk under construction with free reduction: appending the reverse of the last edge cancels it.
struct Walk {
  std::vector<int> vertices, edges;
  void start(int v) { vertices.assign(1, v), edges.clear(); }
  void step(int e, int to) {
    if (!edges.empty() && edges.back() == e) {  // backtracking a -> b -> a
      edges.pop_back();
      vertices.pop_back();
    } else {
      edges.push_back(e);
      vertices.push_back(to);
    }
  }
  // Appends a cut path forwards (from its first to its last vertex) or backwards; the walk must end at its start.
  void append(const CutPath& p, bool forward) {
    const int m = static_cast<int>(p.edges.size());
    for (int i = 0; i < m; ++i) {
      const int k = forward ? i : m - 1 - i;
      step(p.edges[k], forward ? p.vertices[k + 1] : p.vertices[k]);
    }
  }
  // Closed walks: cancel backtracking across the closing vertex.
  void reduce_cyclically() {
    while (edges.size() >= 2 && edges.front() == edges.back()) {
      edges.pop_back();
      vertices.pop_back();
      edges.erase(edges.begin());
      vertices.erase(vertices.begin());
    }
  }
};

// The cotree T* rooted per component: parent face and the dual edge to it, and the depth.
struct RootedCotree {
  std::vector<int> parent, parent_edge, depth;
  RootedCotree(const Mesh& mesh, const CutGraph& graph) {
    const int nf = mesh.num_faces();
    parent.assign(static_cast<std::size_t>(nf), -1);
    parent_edge.assign(static_cast<std::size_t>(nf), -1);
    depth.assign(static_cast<std::size_t>(nf), -1);
    std::vector<int> queue;
    for (int r = 0; r < nf; ++r) {
      if (depth[r] >= 0) continue;
      depth[r] = 0;
      queue.assign(1, r);
      for (std::size_t q = 0; q < queue.size(); ++q) {
        const int f = queue[q];
        for (int k = 0; k < 3; ++k) {
          const int e = mesh.FE()(f, k);
          if (!graph.cotree[e]) continue;
          const int g = mesh.neighbor(f, k);
          if (depth[g] >= 0) continue;
          depth[g] = depth[f] + 1;
          parent[g] = f;
          parent_edge[g] = e;
          queue.push_back(g);
        }
      }
    }
  }
  // The face path from a to b in T*: faces a … b and the edges between them.
  void path(int a, int b, std::vector<int>& faces, std::vector<int>& edges) const {
    std::vector<int> up_a{a}, up_a_edges, up_b{b}, up_b_edges;
    while (a != b) {
      if (depth[a] >= depth[b]) {
        up_a_edges.push_back(parent_edge[a]);
        a = parent[a];
        up_a.push_back(a);
      } else {
        up_b_edges.push_back(parent_edge[b]);
        b = parent[b];
        up_b.push_back(b);
      }
      if (a < 0 || b < 0) throw TopologyError("homology_basis: cotree path between faces of different components");
    }
    faces = up_a;
    faces.insert(faces.end(), up_b.rbegin() + 1, up_b.rend());
    edges = up_a_edges;
    edges.insert(edges.end(), up_b_edges.rbegin(), up_b_edges.rend());
  }
};

// Local index k of edge e in face f (FE(f,k) == e).
int local_edge(const Mesh& mesh, int f, int e) {
  for (int k = 0; k < 3; ++k)
    if (mesh.FE()(f, k) == e) return k;
  throw TopologyError("homology_basis: edge " + std::to_string(e) + " is not an edge of face " + std::to_string(f));
}

Complex edge_midpoint(const Mesh& mesh, int f, int e) {
  const int k = local_edge(mesh, f, e);
  return 0.5 * (mesh.corner_local()(f, (k + 1) % 3) + mesh.corner_local()(f, (k + 2) % 3));
}

/// Nodes of the cut graph's root structure: every interior source is a node, all boundary vertices of a component
/// are one node (the identification of [KNP10]).
struct RootNodes {
  std::vector<int> of_vertex;        ///< #V: node of a source, -1 elsewhere
  std::vector<char> is_boundary;     ///< per node
  int size() const { return static_cast<int>(is_boundary.size()); }
};

RootNodes root_nodes(const Mesh& mesh, const CutGraph& graph) {
  RootNodes nodes;
  nodes.of_vertex.assign(static_cast<std::size_t>(mesh.num_vertices()), -1);
  std::vector<int> boundary_node(static_cast<std::size_t>(mesh.num_components()), -1);
  int count = 0;
  for (const int s : graph.sources) {
    if (mesh.is_boundary_vertex(s)) {
      int& b = boundary_node[mesh.vertex_component()[s]];
      if (b < 0) b = count++;
      nodes.of_vertex[s] = b;
    } else {
      nodes.of_vertex[s] = count++;
    }
  }
  nodes.is_boundary.assign(static_cast<std::size_t>(count), 0);
  for (const int b : boundary_node)
    if (b >= 0) nodes.is_boundary[b] = 1;
  return nodes;
}

/// A cut path traversed towards `node`: forward = from its first to its last vertex.
struct Link {
  int node, path;
  bool forward;
};

/// Spanning forest of the node graph whose edges are the cut paths, shortest paths first; each other path (in
/// `closing`, ascending) closes one fundamental cycle.
struct PathForest {
  std::vector<std::vector<Link>> links;  ///< per node: the forest's paths at it
  std::vector<int> closing;

  PathForest(const CutGraph& graph, const RootNodes& nodes) : links(static_cast<std::size_t>(nodes.size())) {
    const int np = static_cast<int>(graph.paths.size());
    std::vector<int> order(static_cast<std::size_t>(np));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const CutPath &pa = graph.paths[a], &pb = graph.paths[b];
      return pa.length != pb.length ? pa.length < pb.length : pa.leftover_edge < pb.leftover_edge;
    });
    detail::UnionFind forest(nodes.size());
    for (const int i : order) {
      const CutPath& p = graph.paths[i];
      const int a = nodes.of_vertex[p.vertices.front()], b = nodes.of_vertex[p.vertices.back()];
      if (forest.unite(a, b)) {
        links[a].push_back({b, i, true});
        links[b].push_back({a, i, false});
      } else {
        closing.push_back(i);
      }
    }
    std::sort(closing.begin(), closing.end());
  }

  /// The links from node `from` to node `to` in the forest (BFS; at most |B| + #components nodes).
  std::vector<Link> path(int from, int to) const {
    const std::size_t n = links.size();
    std::vector<int> via(n, -2), via_link(n, -1);
    std::vector<int> queue{from};
    via[from] = -1;
    for (std::size_t q = 0; q < queue.size() && via[to] == -2; ++q)
      for (int l = 0; l < static_cast<int>(links[queue[q]].size()); ++l) {
        const int next = links[queue[q]][l].node;
        if (via[next] != -2) continue;
        via[next] = queue[q];
        via_link[next] = l;
        queue.push_back(next);
      }
    std::vector<Link> steps;
    for (int k = to; k != from; k = via[k]) steps.push_back(links[via[k]][via_link[k]]);
    std::reverse(steps.begin(), steps.end());
    return steps;
  }
};

/// The generator closed by path i: p itself, then back through the forest, opened where it passes through a
/// boundary node (at most once: the node cycle is simple).
HomologyGenerator generator_of(const CutGraph& graph, const RootNodes& nodes, const PathForest& forest, int i) {
  const CutPath& p = graph.paths[i];
  const int end = nodes.of_vertex[p.vertices.back()], start = nodes.of_vertex[p.vertices.front()];
  std::vector<Link> segments{{end, i, true}};
  for (const Link& l : forest.path(end, start)) segments.push_back(l);
  std::size_t first = 0;
  bool open = false;
  for (std::size_t s = 0; s < segments.size(); ++s)
    if (nodes.is_boundary[segments[s].node]) {
      first = (s + 1) % segments.size();
      open = true;
    }
  Walk walk;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const Link& l = segments[(first + s) % segments.size()];
    const CutPath& q = graph.paths[l.path];
    if (s == 0) walk.start(l.forward ? q.vertices.front() : q.vertices.back());
    walk.append(q, l.forward);
  }
  if (!open) walk.reduce_cyclically();
  HomologyGenerator gen;
  gen.vertices = std::move(walk.vertices);
  gen.edges = std::move(walk.edges);
  gen.closed = !open;
  gen.crossing_edge = p.leftover_edge;
  if (gen.closed && gen.vertices.front() != gen.vertices.back())
    throw TopologyError("homology_basis: generator through edge " + std::to_string(p.leftover_edge) +
                        " does not close");
  return gen;
}

/// Dual cycle of a generator: from the face left of its crossing edge e_j (as γ_j traverses it) to the right one,
/// back through T*.
DualCycle dual_cycle_of(const Mesh& mesh, const RootedCotree& cotree, const HomologyGenerator& gen) {
  const int e = gen.crossing_edge;
  std::size_t at = 0;
  while (at < gen.edges.size() && gen.edges[at] != e) ++at;
  if (at == gen.edges.size())
    throw TopologyError("homology_basis: leftover edge " + std::to_string(e) + " cancelled from its generator");
  const bool positive = gen.vertices[at] == mesh.E()(e, 0);  // traversed along the edge's orientation
  const int left = mesh.EF()(e, positive ? 0 : 1), right = mesh.EF()(e, positive ? 1 : 0);
  DualCycle dual;
  std::vector<int> back_faces, back_edges;
  cotree.path(right, left, back_faces, back_edges);
  dual.faces.push_back(left);
  dual.faces.insert(dual.faces.end(), back_faces.begin(), back_faces.end() - 1);
  dual.edges.push_back(e);
  dual.edges.insert(dual.edges.end(), back_edges.begin(), back_edges.end());
  return dual;
}

}  // namespace

HomologyBasis homology_basis(const Mesh& mesh, const CutGraph& graph) {
  const RootNodes nodes = root_nodes(mesh, graph);
  const PathForest forest(graph, nodes);
  const RootedCotree cotree(mesh, graph);
  HomologyBasis basis;
  std::vector<Eigen::Triplet<Complex>> period_entries;
  for (const int i : forest.closing) {
    HomologyGenerator gen = generator_of(graph, nodes, forest, i);
    DualCycle dual = dual_cycle_of(mesh, cotree, gen);
    // Period operator row: segment from the entry to the exit midpoint in every face of γ_j*.
    const int row = static_cast<int>(basis.generators.size());
    const std::size_t n = dual.faces.size();
    for (std::size_t k = 0; k < n; ++k) {
      const int f = dual.faces[k];
      const int in = dual.edges[(k + n - 1) % n], out = dual.edges[k];
      period_entries.emplace_back(row, f, edge_midpoint(mesh, f, out) - edge_midpoint(mesh, f, in));
    }
    basis.generators.push_back(std::move(gen));
    basis.dual_cycles.push_back(std::move(dual));
  }
  basis.period_operator.resize(basis.size(), mesh.num_faces());
  basis.period_operator.setFromTriplets(period_entries.begin(), period_entries.end());
  return basis;
}

Eigen::VectorXd periods(const HomologyBasis& basis, const VectorField& X) {
  if (X.size() != basis.period_operator.cols())
    throw InputError("", 0,
                     "periods: field has " + std::to_string(X.size()) + " faces, mesh has " +
                         std::to_string(basis.period_operator.cols()));
  return (basis.period_operator.conjugate() * X).real();
}

}  // namespace quadcover
