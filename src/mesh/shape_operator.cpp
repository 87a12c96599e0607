#include "mesh/shape_operator.h"

#include <cmath>

namespace quadcover {

Eigen::VectorXd signed_dihedral_angles(const Mesh& mesh) {
  const int ne = mesh.num_edges();
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(ne);
  const auto& N = mesh.face_normals();
  for (int e = 0; e < ne; ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    const Eigen::Vector3d ns = N.row(mesh.EF()(e, 0)), nt = N.row(mesh.EF()(e, 1));
    const Eigen::Vector3d d = (mesh.V().row(mesh.E()(e, 1)) - mesh.V().row(mesh.E()(e, 0))).normalized();
    // s lies left of E0 -> E1; on a convex edge n_t tilts to the right, so (n_s × n_t)·ê > 0.
    beta[e] = std::atan2(ns.cross(nt).dot(d), ns.dot(nt));
  }
  return beta;
}

Eigen::Matrix3d edge_shape_operator(const Mesh& mesh, int e) {
  if (mesh.is_boundary_edge(e)) return Eigen::Matrix3d::Zero();
  const auto& N = mesh.face_normals();
  const Eigen::Vector3d ns = N.row(mesh.EF()(e, 0)), nt = N.row(mesh.EF()(e, 1));
  const Eigen::Vector3d edge = mesh.V().row(mesh.E()(e, 1)) - mesh.V().row(mesh.E()(e, 0));
  const double len = edge.norm();
  const Eigen::Vector3d d = edge / len;
  const double beta = std::atan2(ns.cross(nt).dot(d), ns.dot(nt));
  Eigen::Vector3d ne = ns + nt;
  // |β| = π (a folded-over edge) has no bisector; any unit normal ⟂ e serves, the operator is then ±2‖e‖ u uᵀ.
  ne = ne.norm() > 1e-12 ? Eigen::Vector3d(ne.normalized()) : ns;
  const Eigen::Vector3d u = d.cross(ne).normalized();
  // 2‖e‖cos(α_e/2) with α_e = π - β_e (thesis 1.1).
  return 2.0 * len * std::sin(0.5 * beta) * (u * u.transpose());
}

Eigen::MatrixX3d vertex_normals(const Mesh& mesh) {
  Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(mesh.num_vertices(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) N.row(mesh.F()(f, k)) += mesh.face_areas()[f] * mesh.face_normals().row(f);
  N.rowwise().normalize();
  return N;
}

std::vector<Eigen::Matrix3d> vertex_shape_operators(const Mesh& mesh) {
  const Eigen::MatrixX3d Nv = vertex_normals(mesh);
  const auto& N = mesh.face_normals();
  std::vector<Eigen::Matrix3d> S(static_cast<std::size_t>(mesh.num_vertices()), Eigen::Matrix3d::Zero());
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    const Eigen::Matrix3d Se = edge_shape_operator(mesh, e);
    Eigen::Vector3d ne = N.row(mesh.EF()(e, 0)) + N.row(mesh.EF()(e, 1));
    if (ne.norm() > 1e-12) ne.normalize();
    for (int j = 0; j < 2; ++j) {
      const int p = mesh.E()(e, j);
      const Eigen::Vector3d np = Nv.row(p);
      const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - np * np.transpose();
      S[static_cast<std::size_t>(p)] += 0.5 * np.dot(ne) * (P * Se * P);
    }
  }
  return S;
}

}  // namespace quadcover
