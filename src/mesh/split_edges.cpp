#include "mesh/split_edges.h"

#include <stdexcept>
#include <string>

namespace quadcover {

SplitMesh split_edges_at_midpoints(const Mesh& mesh, const std::vector<int>& edges) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  std::vector<int> midpoint(static_cast<std::size_t>(mesh.num_edges()), -1);
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const int e = edges[k];
    if (e < 0 || e >= mesh.num_edges() || midpoint[e] >= 0)
      throw std::invalid_argument("split_edges_at_midpoints: edge " + std::to_string(e) + " is not a new mesh edge");
    midpoint[e] = nv + static_cast<int>(k);
  }
  SplitMesh out;
  out.V.resize(nv + static_cast<Eigen::Index>(edges.size()), 3);
  out.V.topRows(nv) = mesh.V();
  for (std::size_t k = 0; k < edges.size(); ++k)
    out.V.row(nv + static_cast<Eigen::Index>(k)) =
        0.5 * (mesh.V().row(mesh.E()(edges[k], 0)) + mesh.V().row(mesh.E()(edges[k], 1)));
  std::vector<Eigen::RowVector3i> faces;
  std::vector<int> parents;
  faces.reserve(static_cast<std::size_t>(nf) + 2 * edges.size());
  for (int f = 0; f < nf; ++f)  // untouched faces first, in order
    if (midpoint[mesh.FE()(f, 0)] < 0 && midpoint[mesh.FE()(f, 1)] < 0 && midpoint[mesh.FE()(f, 2)] < 0) {
      faces.push_back(mesh.F().row(f));
      parents.push_back(f);
    }
  for (int f = 0; f < nf; ++f) {
    // The boundary polygon of f with the midpoints inserted: corner c, then the midpoint of the edge c → c+1
    // (face edge k = c + 2 is opposite corner c + 2).
    std::vector<int> ring;
    int start = -1;
    for (int c = 0; c < 3; ++c) {
      ring.push_back(mesh.F()(f, c));
      const int m = midpoint[mesh.FE()(f, (c + 2) % 3)];
      if (m < 0) continue;
      if (start < 0) start = static_cast<int>(ring.size());
      ring.push_back(m);
    }
    if (start < 0) continue;
    const int n = static_cast<int>(ring.size());
    for (int i = 1; i + 1 < n; ++i) {  // fan from ring[start] over the other consecutive pairs
      faces.emplace_back(ring[start], ring[(start + i) % n], ring[(start + i + 1) % n]);
      parents.push_back(f);
    }
  }
  out.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t t = 0; t < faces.size(); ++t) out.F.row(static_cast<Eigen::Index>(t)) = faces[t];
  out.parent_face = std::move(parents);
  return out;
}

}  // namespace quadcover
