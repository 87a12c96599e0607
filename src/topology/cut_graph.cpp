#include "topology/cut_graph.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <string>
#include <utility>

#include "common/errors.h"
#include "common/union_find.h"

namespace quadcover {
namespace {

// Vertex -> incident edges, in increasing edge order (CSR).
struct VertexEdges {
  std::vector<int> offsets, edges;
  explicit VertexEdges(const Mesh& mesh) {
    const int nv = mesh.num_vertices(), ne = mesh.num_edges();
    offsets.assign(static_cast<std::size_t>(nv) + 1, 0);
    for (int e = 0; e < ne; ++e) {
      ++offsets[mesh.E()(e, 0) + 1];
      ++offsets[mesh.E()(e, 1) + 1];
    }
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    edges.resize(static_cast<std::size_t>(offsets.back()));
    std::vector<int> fill(offsets.begin(), offsets.end() - 1);
    for (int e = 0; e < ne; ++e) {
      edges[fill[mesh.E()(e, 0)]++] = e;
      edges[fill[mesh.E()(e, 1)]++] = e;
    }
  }
};

Eigen::VectorXd checked_weights(const Mesh& mesh, const CutGraphOptions& options) {
  if (!options.edge_weights) return mesh.edge_lengths();
  const Eigen::VectorXd& w = *options.edge_weights;
  if (w.size() != mesh.num_edges())
    throw InputError(
        "", 0,
        "cut_graph: " + std::to_string(w.size()) + " edge weights for " + std::to_string(mesh.num_edges()) + " edges");
  for (int e = 0; e < w.size(); ++e)
    if (!(w[e] > 0) || !std::isfinite(w[e]))
      throw InputError("", 0, "cut_graph: edge weight " + std::to_string(e) + " is not positive and finite");
  return w;
}

// Tree path from v up to its root: v, parent(v), …, root (vertices) and the edges between them.
void path_to_root(const Mesh& mesh, const CutGraph& g, int v, std::vector<int>& vertices, std::vector<int>& edges) {
  vertices.assign(1, v);
  edges.clear();
  while (g.parent_edge[v] >= 0) {
    const int e = g.parent_edge[v];
    edges.push_back(e);
    v = mesh.E()(e, 0) + mesh.E()(e, 1) - v;
    vertices.push_back(v);
  }
}

/// Sources: B ∪ ∂M, plus a root (the lowest vertex) for each component without base or boundary vertices ([KNP10]).
std::vector<int> cut_sources(const Mesh& mesh, std::span<const int> base) {
  const int nv = mesh.num_vertices();
  std::vector<char> is_source(static_cast<std::size_t>(nv), 0);
  for (const int v : base) {
    if (v < 0 || v >= nv)
      throw InputError("", 0,
                       "cut_graph: base vertex " + std::to_string(v) + " out of range [0, " + std::to_string(nv) + ")");
    is_source[v] = 1;
  }
  for (int v = 0; v < nv; ++v)
    if (mesh.is_boundary_vertex(v)) is_source[v] = 1;
  std::vector<char> component_has_source(static_cast<std::size_t>(mesh.num_components()), 0);
  for (int v = 0; v < nv; ++v)
    if (is_source[v]) component_has_source[mesh.vertex_component()[v]] = 1;
  for (int v = 0; v < nv; ++v) {
    const int c = mesh.vertex_component()[v];
    if (!component_has_source[c]) component_has_source[c] = is_source[v] = 1;
  }
  std::vector<int> sources;
  for (int v = 0; v < nv; ++v)
    if (is_source[v]) sources.push_back(v);
  return sources;
}

/// Step 1: shortest-path forest T from all sources at once (Dijkstra; ties resolved by vertex index): parent_edge,
/// root, distance.
void shortest_path_forest(const Mesh& mesh, const Eigen::VectorXd& w, CutGraph& g) {
  const int nv = mesh.num_vertices();
  const VertexEdges adjacency(mesh);
  g.parent_edge = Eigen::VectorXi::Constant(nv, -1);
  g.root = Eigen::VectorXi::Constant(nv, -1);
  g.distance = Eigen::VectorXd::Constant(nv, std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (const int s : g.sources) {
    g.distance[s] = 0;
    g.root[s] = s;
    queue.push({0.0, s});
  }
  std::vector<char> done(static_cast<std::size_t>(nv), 0);
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (done[v]) continue;
    done[v] = 1;
    for (int i = adjacency.offsets[v]; i < adjacency.offsets[v + 1]; ++i) {
      const int e = adjacency.edges[i];
      const int u = mesh.E()(e, 0) + mesh.E()(e, 1) - v;
      const double du = d + w[e];
      if (!done[u] && du < g.distance[u]) {
        g.distance[u] = du;
        g.parent_edge[u] = e;
        g.root[u] = g.root[v];
        queue.push({du, u});
      }
    }
  }
}

/// Step 2: maximum spanning tree T* of the dual of G \ T, weighted by |σ(e)| (Kruskal; ties by edge index): the
/// cotree flags. Boundary edges are collapsed by the identification and have no dual edge. Returns the edges
/// neither in T nor crossed by T* (ascending); sigma gets |σ(e)| of every candidate edge.
std::vector<int> cotree_leftovers(const Mesh& mesh, const Eigen::VectorXd& w, CutGraph& g, std::vector<double>& sigma) {
  const int ne = mesh.num_edges();
  std::vector<char> in_tree(static_cast<std::size_t>(ne), 0);
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (g.parent_edge[v] >= 0) in_tree[g.parent_edge[v]] = 1;
  std::vector<int> candidates;
  for (int e = 0; e < ne; ++e)
    if (!in_tree[e] && !mesh.is_boundary_edge(e)) candidates.push_back(e);
  sigma.assign(static_cast<std::size_t>(ne), 0.0);
  for (const int e : candidates) sigma[e] = g.distance[mesh.E()(e, 0)] + g.distance[mesh.E()(e, 1)] + w[e];
  std::sort(candidates.begin(), candidates.end(),
            [&](int a, int b) { return sigma[a] != sigma[b] ? sigma[a] > sigma[b] : a < b; });
  g.cotree = Eigen::VectorXi::Zero(ne);
  detail::UnionFind faces(mesh.num_faces());
  std::vector<int> leftover;
  for (const int e : candidates) {
    if (faces.unite(mesh.EF()(e, 0), mesh.EF()(e, 1)))
      g.cotree[e] = 1;
    else
      leftover.push_back(e);
  }
  std::sort(leftover.begin(), leftover.end());
  return leftover;
}

/// Each component's source nodes (interior sources, plus one node for the whole boundary) are joined by
/// nodes - 1 of its paths; every further path closes a loop.
int count_loops(const Mesh& mesh, const CutGraph& g) {
  std::vector<int> nodes(static_cast<std::size_t>(mesh.num_components()), 0);
  std::vector<char> boundary_counted(static_cast<std::size_t>(mesh.num_components()), 0);
  for (const int s : g.sources) {
    const int c = mesh.vertex_component()[s];
    if (!mesh.is_boundary_vertex(s))
      ++nodes[c];
    else if (!boundary_counted[c])
      boundary_counted[c] = 1, ++nodes[c];
  }
  int loops = static_cast<int>(g.paths.size());
  for (const int n : nodes) loops -= n - 1;
  return loops;
}

}  // namespace

CutGraph cut_graph(const Mesh& mesh, std::span<const int> base, const CutGraphOptions& options) {
  const Eigen::VectorXd w = checked_weights(mesh, options);
  CutGraph g;
  g.sources = cut_sources(mesh, base);
  shortest_path_forest(mesh, w, g);
  std::vector<double> sigma;
  const std::vector<int> leftover = cotree_leftovers(mesh, w, g, sigma);
  // Step 3: σ(e) for every leftover edge; undoing the identification makes it a path between two sources.
  g.cut = Eigen::VectorXi::Zero(mesh.num_edges());
  std::vector<int> up0, up0_edges, up1, up1_edges;
  for (const int e : leftover) {
    path_to_root(mesh, g, mesh.E()(e, 0), up0, up0_edges);
    path_to_root(mesh, g, mesh.E()(e, 1), up1, up1_edges);
    CutPath p;
    p.leftover_edge = e;
    p.length = sigma[e];
    p.vertices.assign(up0.rbegin(), up0.rend());
    p.vertices.insert(p.vertices.end(), up1.begin(), up1.end());
    p.edges.assign(up0_edges.rbegin(), up0_edges.rend());
    p.edges.push_back(e);
    p.edges.insert(p.edges.end(), up1_edges.begin(), up1_edges.end());
    for (const int c : p.edges) g.cut[c] = 1;
    g.paths.push_back(std::move(p));
  }
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (g.cut[e]) g.total_length += w[e];
  g.num_loops = count_loops(mesh, g);
  return g;
}

}  // namespace quadcover
