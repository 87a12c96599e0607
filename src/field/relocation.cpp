#include "field/relocation.h"

#include <algorithm>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "field/indices.h"

namespace quadcover {

namespace {
// The edge joining vertices a and b, or -1.
int edge_between(const Mesh& mesh, int a, int b) {
  for (const auto& c : mesh.fan(a)) {
    for (int k : {(c.corner + 1) % 3, (c.corner + 2) % 3}) {
      const int e = mesh.FE()(c.face, k);
      if ((mesh.E()(e, 0) == a && mesh.E()(e, 1) == b) || (mesh.E()(e, 0) == b && mesh.E()(e, 1) == a)) return e;
    }
  }
  return -1;
}

/// Calls step(e, w) for every edge e from v to a vertex w that a relocation path from p may take: interior edges,
/// and none out of a boundary vertex but p (boundary vertices only as the target).
template <class Step>
void relocation_steps(const Mesh& mesh, int p, int v, Step step) {
  if (v != p && mesh.is_boundary_vertex(v)) return;
  for (const auto& c : mesh.fan(v)) {
    const int e = mesh.FE()(c.face, (c.corner + 1) % 3);  // edge {v, corner+2}
    if (!mesh.is_boundary_edge(e)) step(e, mesh.E()(e, 0) == v ? mesh.E()(e, 1) : mesh.E()(e, 0));
  }
}
}  // namespace

std::vector<int> relocation_path(const Mesh& mesh, int p, int q) {
  const int nv = mesh.num_vertices();
  if (p < 0 || p >= nv || q < 0 || q >= nv) throw std::invalid_argument("relocation_path: vertex out of range");
  if (mesh.is_boundary_vertex(p))
    throw std::invalid_argument("relocation_path: vertex " + std::to_string(p) + " lies on the boundary");
  std::vector<double> dist(static_cast<std::size_t>(nv), std::numeric_limits<double>::infinity());
  std::vector<int> prev(static_cast<std::size_t>(nv), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> heap;
  dist[static_cast<std::size_t>(p)] = 0;
  heap.push({0.0, p});
  while (!heap.empty()) {
    const auto [d, v] = heap.top();
    heap.pop();
    if (d > dist[static_cast<std::size_t>(v)]) continue;
    if (v == q) break;
    relocation_steps(mesh, p, v, [&](int e, int w) {
      const double nd = d + mesh.edge_lengths()[e];
      if (nd < dist[static_cast<std::size_t>(w)]) {
        dist[static_cast<std::size_t>(w)] = nd;
        prev[static_cast<std::size_t>(w)] = v;
        heap.push({nd, w});
      }
    });
  }
  if (q != p && prev[static_cast<std::size_t>(q)] < 0)
    throw std::invalid_argument("relocation_path: vertex " + std::to_string(q) + " is not reachable from " +
                                std::to_string(p) + " through interior edges");
  std::vector<int> path{q};
  while (path.back() != p) path.push_back(prev[static_cast<std::size_t>(path.back())]);
  std::reverse(path.begin(), path.end());
  return path;
}

std::vector<std::pair<int, double>> relocation_reach(const Mesh& mesh, int p, double radius) {
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> heap;
  std::unordered_map<int, double> best{{p, 0.0}};  // sparse: the reach is small against the mesh
  std::vector<std::pair<int, double>> out;
  heap.push({0.0, p});
  while (!heap.empty()) {
    const auto [d, v] = heap.top();
    heap.pop();
    if (d > best[v]) continue;
    out.emplace_back(v, d);
    relocation_steps(mesh, p, v, [&](int e, int w) {
      const double next = d + mesh.edge_lengths()[e];
      if (next >= radius) return;
      const auto it = best.find(w);
      if (it != best.end() && it->second <= next) return;
      best[w] = next;
      heap.push({next, w});
    });
  }
  return out;
}

std::vector<MatchingChange> relocation_changes(const Mesh& mesh, const std::vector<int>& path, int quarters) {
  std::vector<MatchingChange> changes;
  if (quarters == 0) return changes;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const int a = path[i], b = path[i + 1];
    const int e = edge_between(mesh, a, b);
    if (e < 0 || mesh.is_boundary_edge(e))
      throw std::invalid_argument("relocation_changes: " + std::to_string(a) + "-" + std::to_string(b) +
                                  " is not an interior edge");
    // EF(e,0) lies left of E0 -> E1. Crossing right -> left of a -> b: if a = E0 that is EF1 -> EF0 (m_e -= δ),
    // otherwise EF0 -> EF1 (m_e += δ). The loop of a (ccw) then crosses it right -> left, that of b left -> right,
    // and with 4·ind = -Σ m the index of a drops by δ while that of b grows by δ.
    changes.push_back({e, mesh.E()(e, 0) == a ? -quarters : quarters});
  }
  return changes;
}

std::vector<MatchingChange> relocate_branch_point(const Mesh& mesh, Eigen::VectorXi& matching, int p, int q) {
  const std::vector<int> path = relocation_path(mesh, p, q);
  const int quarters = matching_quarter_index(mesh, matching)[p];
  const std::vector<MatchingChange> changes = relocation_changes(mesh, path, quarters);
  for (const auto& c : changes) matching[c.edge] += c.delta;
  return changes;
}

}  // namespace quadcover
