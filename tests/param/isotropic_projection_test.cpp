// The analytic projection of an isotropic density's Hessian (param/isotropic_projection.h) against the projection by
// a full 4 × 4 eigen decomposition.
#include "param/isotropic_projection.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "param/untangle.h"

namespace quadcover {
namespace {

Eigen::Matrix4d projected_by_eigen_decomposition(const Eigen::Matrix4d& H) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> es(H);
  return es.eigenvectors() * es.eigenvalues().cwiseMax(0.0).asDiagonal() * es.eigenvectors().transpose();
}

// Random Jacobians of both orientations, nearly degenerate ones, similarities (s1 = s2) and anti-similarities
// (s1 = −s2), at several ε: the untangling density's Hessian projected both ways agrees to round-off, and the
// analytic one is positive semidefinite.
TEST(IsotropicProjection, EqualsTheEigenDecompositionsOnTheUntanglingDensity) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::vector<Eigen::Matrix2d> cases;
  for (int k = 0; k < 200; ++k) cases.push_back((Eigen::Matrix2d() << u(rng), u(rng), u(rng), u(rng)).finished());
  cases.push_back((Eigen::Matrix2d() << 1.3, -0.4, 0.4, 1.3).finished());        // a similarity
  cases.push_back((Eigen::Matrix2d() << 0.7, 0.5, 0.5, -0.7).finished());        // a reflection times a scale
  cases.push_back((Eigen::Matrix2d() << 1.0, 2.0, 0.5, 1.0 + 1e-9).finished());  // det ≈ 0
  cases.push_back(Eigen::Matrix2d::Zero());
  int indefinite = 0;
  for (const double eps : {1.0, 1e-2, 1e-5})
    for (const Eigen::Matrix2d& J : cases) {
      Eigen::Vector4d g;
      Eigen::Matrix4d H;
      untangle_density(J, eps, 1.0, &g, &H);
      const Eigen::Matrix4d expected = projected_by_eigen_decomposition(H);
      const Eigen::Matrix4d got = project_isotropic_hessian(J, H);
      EXPECT_LE((got - expected).norm(), 1e-9 * (1 + H.norm())) << "eps " << eps << "\n" << J;
      EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(got).eigenvalues().minCoeff(), -1e-9 * (1 + H.norm()));
      indefinite += Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(H).eigenvalues().minCoeff() < 0;
    }
  EXPECT_GT(indefinite, 50);  // the projection had work to do
}

// A Hessian that is not of an isotropic density (a coupling of the twist and a scaling mode) is not what the
// projection is for: the result then differs from the eigen decomposition's, which is what the test above rules out.
TEST(IsotropicProjection, SeesOnlyTheIsotropicBlocks) {
  const Eigen::Matrix2d J = (Eigen::Matrix2d() << 1.0, 0.0, 0.0, 0.5).finished();
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  H(0, 1) = H(1, 0) = 0.9;  // couples J00 (a scaling mode) with J01 (twist and flip)
  H(2, 2) = -1.0;
  EXPECT_GT((project_isotropic_hessian(J, H) - projected_by_eigen_decomposition(H)).norm(), 1e-3);
}

}  // namespace
}  // namespace quadcover
