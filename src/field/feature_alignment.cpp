#include "field/feature_alignment.h"

#include <cmath>
#include <numbers>
#include <numeric>

#include "common/union_find.h"
#include "mesh/shape_operator.h"

namespace quadcover {

namespace {

// Keeps the sharp edges that lie on chains of at least `min_edges` sharp edges continuing each other.
void keep_feature_curves(const Mesh& mesh, int min_edges, std::vector<int>& sharp) {
  if (min_edges <= 1 || sharp.empty()) return;
  const int ne = mesh.num_edges();
  std::vector<std::vector<int>> at(static_cast<std::size_t>(mesh.num_vertices()));
  for (int e : sharp)
    for (int j = 0; j < 2; ++j) at[static_cast<std::size_t>(mesh.E()(e, j))].push_back(e);
  detail::UnionFind curves(ne);
  const auto away = [&](int e, int v) {  // unit direction of e leaving v
    const int w = mesh.E()(e, 0) == v ? mesh.E()(e, 1) : mesh.E()(e, 0);
    return Eigen::Vector3d((mesh.V().row(w) - mesh.V().row(v)).normalized());
  };
  const double continues = -std::cos(40.0 * std::numbers::pi / 180.0);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const auto& edges = at[static_cast<std::size_t>(v)];
    for (std::size_t i = 0; i < edges.size(); ++i)
      for (std::size_t j = i + 1; j < edges.size(); ++j)
        if (away(edges[i], v).dot(away(edges[j], v)) < continues)
          curves.unite(edges[i], edges[j]);
  }
  std::vector<int> size(static_cast<std::size_t>(ne), 0);
  for (int e : sharp) ++size[static_cast<std::size_t>(curves.find(e))];
  std::erase_if(sharp, [&](int e) { return size[static_cast<std::size_t>(curves.find(e))] < min_edges; });
}

}  // namespace

FeatureConstraints feature_constraints(const Mesh& mesh, const FeatureOptions& options) {
  const int nf = mesh.num_faces(), ne = mesh.num_edges();
  const Eigen::VectorXd beta = signed_dihedral_angles(mesh);
  const double threshold = options.sharp_angle_degrees * std::numbers::pi / 180.0;
  Eigen::VectorXd strength = Eigen::VectorXd::Zero(ne);
  FeatureConstraints out;
  for (int e = 0; e < ne; ++e) {
    if (mesh.is_boundary_edge(e)) {
      if (options.boundaries) strength[e] = std::numbers::pi;
    } else if (options.sharp_angle_degrees > 0 && std::abs(beta[e]) > threshold) {
      out.feature_edges.push_back(e);
    }
  }
  keep_feature_curves(mesh, options.min_curve_edges, out.feature_edges);
  for (int e : out.feature_edges) strength[e] = std::abs(beta[e]);
  out.constrained.assign(static_cast<std::size_t>(nf), 0);
  out.source_edge.assign(static_cast<std::size_t>(nf), -1);
  out.direction = Eigen::VectorXcd::Zero(nf);
  for (int f = 0; f < nf; ++f) {
    int best = -1;
    for (int k = 0; k < 3; ++k) {
      const int e = mesh.FE()(f, k);
      if (strength[e] == 0) continue;
      if (best < 0) {
        best = k;
        continue;
      }
      const int b = mesh.FE()(f, best);
      if (strength[e] > strength[b] || (strength[e] == strength[b] && mesh.edge_lengths()[e] > mesh.edge_lengths()[b]))
        best = k;
    }
    if (best < 0) continue;
    const Complex d = mesh.edge_vector_local(f, best);
    out.constrained[static_cast<std::size_t>(f)] = 1;
    out.source_edge[static_cast<std::size_t>(f)] = mesh.FE()(f, best);
    out.direction[f] = d / std::abs(d);
  }
  return out;
}

}  // namespace quadcover
