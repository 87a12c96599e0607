#include "field/matching.h"

#include <cmath>
#include <numbers>

namespace quadcover {

Eigen::VectorXd intrinsic_angles(const Mesh& mesh, const Eigen::VectorXcd& X) {
  const int ne = mesh.num_edges();
  Eigen::VectorXd angle = Eigen::VectorXd::Zero(ne);
  for (int e = 0; e < ne; ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    const Complex xs = X[mesh.EF()(e, 0)], xt = X[mesh.EF()(e, 1)];
    const Complex moved = mesh.edge_transport()[e] * xs;
    if (std::abs(xs) == 0 || std::abs(xt) == 0) continue;
    angle[e] = std::arg(xt * std::conj(moved));
  }
  return angle;
}

Eigen::VectorXi straightest_matching(const Mesh& mesh, const Eigen::VectorXcd& X) {
  const Eigen::VectorXd angle = intrinsic_angles(mesh, X);
  Eigen::VectorXi m(angle.size());
  for (Eigen::Index e = 0; e < angle.size(); ++e)
    m[e] = static_cast<int>(std::lround(2.0 * angle[e] / std::numbers::pi));  // (5.1)
  return m;
}

double wrap_angle(double x) {
  const double two_pi = 2 * std::numbers::pi;
  x = std::remainder(x, two_pi);  // [-π, π]
  return x <= -std::numbers::pi ? x + two_pi : x;
}

Eigen::VectorXd field_curvature(const Mesh& mesh, const FrameField& field) {
  Eigen::VectorXd theta = intrinsic_angles(mesh, orthogonalized_frames(field));
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (!mesh.is_boundary_edge(e))
      theta[e] = wrap_angle(theta[e] - 0.5 * std::numbers::pi * field.matching[e]);  // (3.4)
  return theta;
}

FrameField cross_field_with_straightest_matching(const Mesh& mesh, const Eigen::VectorXcd& X) {
  return make_cross_field(X, straightest_matching(mesh, X));
}

Eigen::VectorXd smoothing_edge_weights(const Mesh& mesh) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(mesh.num_edges());
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    const double Ae = (mesh.face_areas()[mesh.EF()(e, 0)] + mesh.face_areas()[mesh.EF()(e, 1)]) / 3.0;
    w[e] = mesh.edge_lengths()[e] * mesh.edge_lengths()[e] / Ae;
  }
  return w;
}

double smoothing_energy(const Mesh& mesh, const FrameField& field) {
  const Eigen::VectorXd theta = field_curvature(mesh, field);
  return (smoothing_edge_weights(mesh).array() * theta.array().square()).sum();
}

}  // namespace quadcover
