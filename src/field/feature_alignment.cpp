#include "field/feature_alignment.h"

#include <cmath>
#include <numbers>

#include "mesh/shape_operator.h"

namespace quadcover {

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
      strength[e] = std::abs(beta[e]);
      out.feature_edges.push_back(e);
    }
  }
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
