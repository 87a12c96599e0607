// The positive semidefinite part of an isotropic density's Hessian (see isotropic_projection.h).
#include "param/isotropic_projection.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace quadcover {

namespace {

/// vec(U X Vᵀ) in the order (00, 01, 10, 11) for the 2 × 2 matrix X.
Eigen::Vector4d vec_of(const Eigen::Matrix2d& U, const Eigen::Matrix2d& X, const Eigen::Matrix2d& Vt) {
  const Eigen::Matrix2d M = U * X * Vt;
  return {M(0, 0), M(0, 1), M(1, 0), M(1, 1)};
}

Eigen::Matrix2d rotation(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return (Eigen::Matrix2d() << c, -s, s, c).finished();
}

}  // namespace

Eigen::Matrix4d project_isotropic_hessian(const Eigen::Matrix2d& J, const Eigen::Matrix4d& hessian) {
  // Signed SVD in closed form: J = Rot(φ) diag(q + r, q − r) Rot(θ), both factors rotations.
  const double e = (J(0, 0) + J(1, 1)) / 2, f = (J(0, 0) - J(1, 1)) / 2;
  const double g = (J(1, 0) + J(0, 1)) / 2, h = (J(1, 0) - J(0, 1)) / 2;
  const double a1 = std::atan2(g, f), a2 = std::atan2(h, e);
  const Eigen::Matrix2d U = rotation((a2 + a1) / 2), Vt = rotation((a2 - a1) / 2);
  const Eigen::Matrix2d twist = (Eigen::Matrix2d() << 0, -1, 1, 0).finished() / std::sqrt(2.0);
  const Eigen::Matrix2d flip = (Eigen::Matrix2d() << 0, 1, 1, 0).finished() / std::sqrt(2.0);
  Eigen::Matrix<double, 4, 2> scaling;  // the block on U e_k e_kᵀ Vᵀ
  scaling.col(0) = vec_of(U, (Eigen::Matrix2d() << 1, 0, 0, 0).finished(), Vt);
  scaling.col(1) = vec_of(U, (Eigen::Matrix2d() << 0, 0, 0, 1).finished(), Vt);
  Eigen::Matrix4d projected = Eigen::Matrix4d::Zero();
  for (const Eigen::Matrix2d* mode : {&twist, &flip}) {
    const Eigen::Vector4d t = vec_of(U, *mode, Vt);
    projected += std::max(t.dot(hessian * t), 0.0) * t * t.transpose();
  }
  const Eigen::Matrix2d block = scaling.transpose() * hessian * scaling;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(block);
  const Eigen::Matrix<double, 4, 2> Q = scaling * es.eigenvectors();
  projected += Q * es.eigenvalues().cwiseMax(0.0).asDiagonal() * Q.transpose();
  return projected;
}

}  // namespace quadcover
