#pragma once
// Analytic principal curvatures of implicit surfaces F(x) = 0, for comparing discrete curvature frames:
// the shape operator is S = P H P / |∇F|, P = I - n nᵀ, n = ∇F/|∇F|, H the Hessian of F. With n pointing
// outward (F < 0 inside) a sphere of radius r gets κ = 1/r, the sign convention of mesh/shape_operator.h.
#include <Eigen/Dense>
#include <complex>
#include <functional>

#include "mesh/mesh.h"

namespace quadcover::testing {

struct Implicit {
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> gradient;
  std::function<Eigen::Matrix3d(const Eigen::Vector3d&)> hessian;
};

inline Implicit implicit_cylinder(double r) {  // x² + y² - r²
  (void)r;
  return {[](const Eigen::Vector3d& x) { return Eigen::Vector3d(2 * x.x(), 2 * x.y(), 0); },
          [](const Eigen::Vector3d&) { return Eigen::Vector3d(2, 2, 0).asDiagonal().toDenseMatrix(); }};
}
inline Implicit implicit_ellipsoid(double a, double b, double c) {  // x²/a² + y²/b² + z²/c² - 1
  const Eigen::Vector3d d(2 / (a * a), 2 / (b * b), 2 / (c * c));
  return {[d](const Eigen::Vector3d& x) { return Eigen::Vector3d(d.cwiseProduct(x)); },
          [d](const Eigen::Vector3d&) { return d.asDiagonal().toDenseMatrix(); }};
}
inline Implicit implicit_saddle(double c) {  // c(x² - y²) - z, "outward" = +z side up
  return {[c](const Eigen::Vector3d& x) { return Eigen::Vector3d(2 * c * x.x(), -2 * c * x.y(), -1); },
          [c](const Eigen::Vector3d&) { return Eigen::Vector3d(2 * c, -2 * c, 0).asDiagonal().toDenseMatrix(); }};
}

/// Analytic principal frame at face t's centroid, in t's basis, oriented like the face normal.
struct AnalyticFrame {
  std::complex<double> direction;  // unit, κ_max direction
  double kappa_max, kappa_min;
};
inline AnalyticFrame analytic_frame(const Mesh& mesh, int t, const Implicit& surf) {
  const Eigen::Vector3d x =
      (mesh.V().row(mesh.F()(t, 0)) + mesh.V().row(mesh.F()(t, 1)) + mesh.V().row(mesh.F()(t, 2))) / 3.0;
  Eigen::Vector3d g = surf.gradient(x);
  const double len = g.norm();
  const Eigen::Vector3d n = g / len;
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
  Eigen::Matrix3d S = P * surf.hessian(x) * P / len;
  if (n.dot(mesh.face_normals().row(t)) < 0) S = -S;
  const Eigen::Vector3d b1 = mesh.face_basis1().row(t), b2 = mesh.face_basis2().row(t);
  const double a = b1.dot(S * b1), b = b1.dot(S * b2), c = b2.dot(S * b2);
  const std::complex<double> q(0.5 * (a - c), b);
  return {std::polar(1.0, 0.5 * std::arg(q)), 0.5 * (a + c) + std::abs(q), 0.5 * (a + c) - std::abs(q)};
}

/// Angle in [0, π/2] between two directions taken modulo π (lines).
inline double line_angle(std::complex<double> u, std::complex<double> v) {
  return 0.5 * std::abs(std::arg((u * u) * std::conj(v * v)));
}

}  // namespace quadcover::testing
