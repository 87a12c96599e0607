#include "pipeline/boundary_loop_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "param/density.h"

namespace quadcover {
namespace {

/// Per face of mesh, the boundary loop it touches (by an edge first, else by a vertex), or -1.
std::vector<int> face_loops(const Mesh& mesh) {
  std::vector<int> loop_of(static_cast<std::size_t>(mesh.num_faces()), -1);
  const auto& loops = mesh.boundary_loops();
  for (int l = 0; l < static_cast<int>(loops.size()); ++l)
    for (int v : loops[l])
      for (const Mesh::FanCorner& fc : mesh.fan(v))
        if (loop_of[fc.face] < 0) loop_of[fc.face] = l;
  for (int l = 0; l < static_cast<int>(loops.size()); ++l)
    for (int e : mesh.boundary_loop_edges()[l]) loop_of[std::max(mesh.EF()(e, 0), mesh.EF()(e, 1))] = l;
  return loop_of;
}

/// Counts into loops[l].non_quads the non-quad faces of q with a boundary vertex over a face of loop l, and marks
/// the loops that no boundary vertex of q lies over as closed over.
void count_non_quads(const Mesh& mesh, const QuadMesh& q, std::vector<BoundaryLoopCheck>& loops) {
  const std::vector<int> loop_of = face_loops(mesh);
  const std::vector<char> on_boundary = quad_boundary_vertices(q);
  const auto loop_under = [&](int v) {
    const int t = q.source_face[v];
    return on_boundary[v] && t >= 0 && t < mesh.num_faces() ? loop_of[t] : -1;
  };
  std::vector<char> followed(loops.size(), 0);
  for (int v = 0; v < q.num_vertices(); ++v)
    if (const int l = loop_under(v); l >= 0) followed[l] = 1;
  for (std::size_t l = 0; l < loops.size(); ++l) loops[l].closed_over = !followed[l];
  for (const auto& f : q.faces) {
    if (f.size() == 4) continue;
    std::vector<int> touched;
    for (int v : f)
      if (const int l = loop_under(v); l >= 0) touched.push_back(l);
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (int l : touched) ++loops[l].non_quads;
  }
}

/// Why loop l is not all quads: too short for a ring of quads, or the reason that leaves the most of its edges
/// off the integer iso-lines (no line at all: not aligned with the field).
std::string loop_reason(const BoundaryLoopCheck& loop, int map_edges, const std::map<std::string, int>& free_edges,
                        const CurveAlignmentOptions& alignment) {
  char text[160];
  const std::string closed = loop.closed_over ? "closed over by the quads: " : "";
  if (loop.length < kShortestQuadLoop) {
    const double factor = std::pow(kShortestQuadLoop / std::max(loop.length, 1e-9), 2);
    std::snprintf(text, sizeof text,
                  "%.1f grid units around, too short for a ring of quads (%.0f) at this density; it is that long "
                  "at about %.1f times the quads",
                  loop.length, kShortestQuadLoop, factor);
    return closed + text;
  }
  if (loop.closed_over) return "closed over by the quads (see the report's extraction)";
  const auto most = std::max_element(free_edges.begin(), free_edges.end(),
                                     [](const auto& a, const auto& b) { return a.second < b.second; });
  if (most == free_edges.end() || most->second == 0)
    return "its lines are on integer iso-lines; the extraction left these faces (see the report's extraction)";
  int off = 0;
  for (const auto& [why, edges] : free_edges) off += edges;
  std::snprintf(text, sizeof text,
                "%.0f %% of its edges are off the integer iso-lines, %.0f %% because: ", 100.0 * off / map_edges,
                100.0 * most->second / map_edges);
  std::string why = text + most->first;
  const bool pinnable = most->first != "shorter than the minimum length" && most->first != "not aligned with the field";
  if (alignment.round_with_periods || !pinnable) return why;
  std::snprintf(text, sizeof text, " (--round-curves true puts lines of %g or more grid units on iso-lines)",
                alignment.limits.min_length);
  return why + text;
}

}  // namespace

std::vector<BoundaryLoopCheck> check_boundary_loops(const Mesh& mesh, int input_vertices, const Parameterization& map,
                                                    const QuadMesh& quads, const CurveAlignmentOptions& alignment) {
  const auto& loop_vertices = mesh.boundary_loops();
  const int n = static_cast<int>(loop_vertices.size());
  std::vector<BoundaryLoopCheck> loops(static_cast<std::size_t>(n));
  std::vector<int> edge_loop(static_cast<std::size_t>(mesh.num_edges()), -1);
  const Eigen::VectorXd rho = face_density(mesh, map.component_density);  // grid units per h of each component
  for (int l = 0; l < n; ++l) {
    BoundaryLoopCheck& c = loops[l];
    c.first_vertex = input_vertices;
    for (int v : loop_vertices[l])
      if (v < input_vertices) c.first_vertex = std::min(c.first_vertex, v);
    c.at = mesh.V().row(c.first_vertex).transpose();
    ++c.first_vertex;
    for (int v : loop_vertices[l]) c.edges += v < input_vertices;  // an input vertex starts each input edge
    double length = 0;
    for (int e : mesh.boundary_loop_edges()[l]) {
      edge_loop[e] = l;
      length += (mesh.V().row(mesh.E()(e, 0)) - mesh.V().row(mesh.E()(e, 1))).norm();
    }
    const int first_edge = mesh.boundary_loop_edges()[l].front();
    const int loop_face = std::max(mesh.EF()(first_edge, 0), mesh.EF()(first_edge, 1));  // its one face
    c.length = map.edge_length > 0 ? rho[loop_face] * length / map.edge_length : 0;
  }
  std::vector<std::map<std::string, int>> free_edges(static_cast<std::size_t>(n));
  std::vector<int> edges_on_lines(static_cast<std::size_t>(n), 0);
  for (const Parameterization::Curve& curve : map.aligned_curves) {
    const int l = curve.edges.empty() ? -1 : edge_loop[curve.edges.front()];
    if (l < 0) continue;  // a feature line
    ++loops[l].lines;
    loops[l].enforced_lines += curve.enforced;
    edges_on_lines[l] += static_cast<int>(curve.edges.size());
    if (!curve.enforced) free_edges[l][curve.left_free_because] += static_cast<int>(curve.edges.size());
  }
  count_non_quads(mesh, quads, loops);
  for (int l = 0; l < n; ++l) {
    const int map_edges = static_cast<int>(mesh.boundary_loop_edges()[l].size());
    free_edges[l]["not aligned with the field"] = map_edges - edges_on_lines[l];
    if (loops[l].non_quads > 0 || loops[l].closed_over)
      loops[l].reason = loop_reason(loops[l], map_edges, free_edges[l], alignment);
  }
  // Numbered by their lowest input vertex: the same numbers on the input and on a refinement of it.
  std::sort(loops.begin(), loops.end(), [](const auto& a, const auto& b) { return a.first_vertex < b.first_vertex; });
  for (int l = 0; l < n; ++l) loops[l].loop = l + 1;
  return loops;
}

std::vector<std::string> boundary_loop_warnings(const std::vector<BoundaryLoopCheck>& loops) {
  constexpr std::size_t kShown = 5;
  std::vector<const BoundaryLoopCheck*> open;
  for (const BoundaryLoopCheck& l : loops)
    if (l.non_quads > 0 || l.closed_over) open.push_back(&l);
  std::stable_sort(open.begin(), open.end(), [](auto* a, auto* b) {
    return std::pair(a->closed_over, a->non_quads) > std::pair(b->closed_over, b->non_quads);
  });
  std::vector<std::string> w;
  char head[200];
  for (std::size_t i = 0; i < std::min(kShown, open.size()); ++i) {
    const BoundaryLoopCheck& l = *open[i];
    std::snprintf(head, sizeof head,
                  "boundary loop %d (through vertex %d at (%.6g, %.6g, %.6g), %d edges, %.1f grid units): ", l.loop,
                  l.first_vertex, l.at.x(), l.at.y(), l.at.z(), l.edges, l.length);
    const std::string faces = l.non_quads > 0 ? std::to_string(l.non_quads) + " non-quad faces, " : "";
    w.push_back(head + faces + l.reason);
  }
  if (open.size() > kShown)
    w.push_back("and " + std::to_string(open.size() - kShown) +
                " more boundary loops closed over or with non-quad faces in the report's boundary_loops");
  return w;
}

nlohmann::json to_json(const std::vector<BoundaryLoopCheck>& loops) {
  nlohmann::json a = nlohmann::json::array();
  for (const BoundaryLoopCheck& l : loops)
    a.push_back({{"loop", l.loop},
                 {"first_vertex", l.first_vertex},
                 {"at", {l.at.x(), l.at.y(), l.at.z()}},
                 {"edges", l.edges},
                 {"length", l.length},
                 {"lines", l.lines},
                 {"enforced_lines", l.enforced_lines},
                 {"non_quads", l.non_quads},
                 {"closed_over", l.closed_over},
                 {"reason", l.reason.empty() ? nlohmann::json(nullptr) : nlohmann::json(l.reason)}});
  return a;
}

}  // namespace quadcover
