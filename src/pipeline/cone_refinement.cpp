#include "pipeline/cone_refinement.h"

#include <cstdlib>
#include <memory>

#include "field/indices.h"
#include "mesh/split_edges.h"

namespace quadcover {

std::vector<int> unsplit_singularities(const Mesh& mesh, const FrameField& field, int min_quarters) {
  const Eigen::VectorXi q = cross_field_quarter_index(mesh, field);
  std::vector<int> out;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (!mesh.is_boundary_vertex(v) && std::abs(q[v]) >= min_quarters) out.push_back(v);
  return out;
}

void refine_around_vertices(const Mesh& mesh, const std::vector<int>& vertices, CurveRefinement& refinement) {
  if (vertices.empty()) return;
  std::vector<char> at(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (int v : vertices) at[static_cast<std::size_t>(v)] = 1;
  std::vector<int> edges;
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (at[static_cast<std::size_t>(mesh.E()(e, 0))] || at[static_cast<std::size_t>(mesh.E()(e, 1))])
      edges.push_back(e);
  const SplitMesh split = split_edges_at_midpoints(mesh, edges);
  for (int e : edges) refinement.split.push_back({mesh.E()(e, 0), mesh.E()(e, 1)});
  refinement.added_faces += static_cast<int>(split.F.rows()) - mesh.num_faces();
  refinement.mesh = std::make_shared<const Mesh>(Mesh::from_triangles(split.V, split.F));
}

}  // namespace quadcover
