// Frame operations (thesis 3.1: R, (X,Y)^⊥, cross directions) and the intrinsic angle behind the matching (5.1).
#include "field/frame_field.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numbers>
#include <random>

#include "field/matching.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

TEST(FrameOps, SwitchingOperatorIsAComplexStructure) {
  const Complex X(0.3, -1.2), Y(0.7, 0.4);
  const auto twice = frame_switch(X, Y, 2);
  EXPECT_EQ(twice.first, -X);  // R² = -id (3.1)
  EXPECT_EQ(twice.second, -Y);
  EXPECT_EQ(frame_switch(X, Y, 4), std::make_pair(X, Y));
  EXPECT_EQ(frame_switch(X, Y, -1), frame_switch(X, Y, 3));
  // The thesis's R(X,Y) = (-Y, X) is our R'^{-1}.
  EXPECT_EQ(frame_switch(X, Y, -1), std::make_pair(-Y, X));
  for (int k = -5; k <= 5; ++k) {
    // For a cross (Y = iX), R'^k multiplies both vectors by i^k.
    const Complex ik = std::pow(Complex(0, 1), k);
    const auto c = frame_switch(X, Complex(0, 1) * X, k);
    EXPECT_LT(std::abs(c.first - ik * X), 1e-14);
    EXPECT_LT(std::abs(c.second - ik * Complex(0, 1) * X), 1e-14);
    // Orthogonalization commutes with switching: (R'^k(X,Y))^⊥ = i^k (X,Y)^⊥, so matchings carry over.
    const auto g = frame_switch(X, Y, k);
    EXPECT_LT(std::abs(orthogonalized(g.first, g.second) - ik * orthogonalized(X, Y)), 1e-14);
  }
  // (X, JX)^⊥ = (X, JX); (X, -JX)^⊥ = 0 (an orientation-reversing frame has no cross).
  EXPECT_LT(std::abs(orthogonalized(X, Complex(0, 1) * X) - X), 1e-15);
  EXPECT_LT(std::abs(orthogonalized(X, Complex(0, -1) * X)), 1e-15);
}

// The 3D cross directions are unit, tangent, orthogonal, and u is the direction of X^⊥.
TEST(FrameOps, CrossDirectionsInWorld) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  std::mt19937 rng(3);
  FrameField field;
  field.X.resize(mesh.num_faces());
  field.Y.resize(mesh.num_faces());
  for (int t = 0; t < mesh.num_faces(); ++t) {
    field.X[t] = Complex(rng() / 4294967296.0 - 0.5, rng() / 4294967296.0 - 0.5);
    field.Y[t] = Complex(0, 1.3) * field.X[t] + 0.2 * field.X[t];
  }
  const CrossDirections d = cross_directions(mesh, field);
  for (int t = 0; t < mesh.num_faces(); ++t) {
    const Eigen::Vector3d u = d.u.row(t), v = d.v.row(t), n = mesh.face_normals().row(t);
    ASSERT_NEAR(u.norm(), 1, 1e-12);
    ASSERT_NEAR(v.norm(), 1, 1e-12);
    ASSERT_NEAR(u.dot(v), 0, 1e-12);
    ASSERT_NEAR(u.dot(n), 0, 1e-12);
    ASSERT_LT((n.cross(u) - v).norm(), 1e-12);  // v = J u
    const Eigen::Vector3d w = mesh.to_world(t, orthogonalized(field.X[t], field.Y[t]));
    ASSERT_LT((w.normalized() - u).norm(), 1e-12);
  }
}

// ∠_e is measured intrinsically: recompute it by rotating X_s (in 3D) about the shared edge into t's plane and
// measuring the angle to X_t there.
TEST(Matching, IntrinsicAngleEqualsUnfoldedAngle) {
  const Mesh mesh = testing::load_test_mesh("fertility_genus4");
  std::mt19937 rng(4);
  Eigen::VectorXcd X(mesh.num_faces());
  for (int t = 0; t < X.size(); ++t) X[t] = std::polar(1.0, 2 * std::numbers::pi * (rng() / 4294967296.0));
  const Eigen::VectorXd angle = intrinsic_angles(mesh, X);
  const Eigen::VectorXi m = straightest_matching(mesh, X);
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    const Eigen::Vector3d d = (mesh.V().row(mesh.E()(e, 1)) - mesh.V().row(mesh.E()(e, 0))).normalized();
    const Eigen::Vector3d ns = mesh.face_normals().row(s), nt = mesh.face_normals().row(t);
    const double dihedral = std::atan2(ns.cross(nt).dot(d), ns.dot(nt));
    const Eigen::Vector3d xs = Eigen::AngleAxisd(dihedral, d) * mesh.to_world(s, X[s]);
    const Eigen::Vector3d xt = mesh.to_world(t, X[t]);
    const double expected = std::atan2(nt.dot(xs.cross(xt)), xs.dot(xt));
    ASSERT_NEAR(std::remainder(angle[e] - expected, 2 * std::numbers::pi), 0.0, 1e-9) << "edge " << e;
    // (5.1): the residual after m quarter turns is at most π/4.
    ASSERT_LE(std::abs(angle[e] - std::numbers::pi / 2 * m[e]), std::numbers::pi / 4 + 1e-12);
  }
}

}  // namespace
}  // namespace quadcover
