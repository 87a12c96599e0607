#include "pipeline/curve_refinement.h"

#include "mesh/split_edges.h"

namespace quadcover {

std::vector<int> curve_refinement_edges(const Mesh& mesh, const FeatureOptions& features) {
  const int nf = mesh.num_faces(), ne = mesh.num_edges();
  std::vector<char> curve_edge(static_cast<std::size_t>(ne), 0), curve_vertex(mesh.num_vertices(), 0);
  if (features.boundaries)
    for (int e = 0; e < ne; ++e) curve_edge[e] = mesh.is_boundary_edge(e) ? 1 : 0;
  if (has_sharp_features(features))
    for (int e : feature_constraints(mesh, features).feature_edges) curve_edge[e] = 1;
  for (int e = 0; e < ne; ++e)
    if (curve_edge[e]) curve_vertex[mesh.E()(e, 0)] = curve_vertex[mesh.E()(e, 1)] = 1;
  std::vector<char> chosen(static_cast<std::size_t>(ne), 0);
  for (int f = 0; f < nf; ++f) {
    if (!curve_vertex[mesh.F()(f, 0)] || !curve_vertex[mesh.F()(f, 1)] || !curve_vertex[mesh.F()(f, 2)]) continue;
    int best = -1;
    bool done = false;
    for (int k = 0; k < 3; ++k) {
      const int e = mesh.FE()(f, k);
      done = done || chosen[e];
      if (curve_edge[e] || mesh.is_boundary_edge(e)) continue;
      if (best < 0 || mesh.edge_lengths()[e] > mesh.edge_lengths()[best] ||
          (mesh.edge_lengths()[e] == mesh.edge_lengths()[best] && e < best))
        best = e;
    }
    if (!done && best >= 0) chosen[best] = 1;
  }
  std::vector<int> edges;
  for (int e = 0; e < ne; ++e)
    if (chosen[e]) edges.push_back(e);
  return edges;
}

CurveRefinement refine_for_curves(const Mesh& mesh, const FeatureOptions& features) {
  CurveRefinement r;
  const std::vector<int> edges = curve_refinement_edges(mesh, features);
  if (edges.empty()) return r;
  SplitMesh split = split_edges_at_midpoints(mesh, edges);
  for (int e : edges) r.split.push_back({mesh.E()(e, 0), mesh.E()(e, 1)});
  r.added_faces = static_cast<int>(split.F.rows()) - mesh.num_faces();
  r.mesh = std::make_shared<const Mesh>(Mesh::from_triangles(split.V, split.F));
  return r;
}

}  // namespace quadcover
