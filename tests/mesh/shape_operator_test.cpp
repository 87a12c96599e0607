// Hildebrandt–Polthier shape operators (thesis 1.1).
#include "mesh/shape_operator.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "support/test_meshes.h"

namespace quadcover {
namespace {

// S(e) = 2‖e‖cos(α_e/2) u uᵀ: symmetric, rank one, e and the bisector normal in its kernel, trace 2‖e‖sin(β_e/2).
TEST(ShapeOperator, EdgeOperatorStructureOnRealMesh) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const Eigen::VectorXd beta = signed_dihedral_angles(mesh);
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const Eigen::Matrix3d S = edge_shape_operator(mesh, e);
    const Eigen::Vector3d d = mesh.V().row(mesh.E()(e, 1)) - mesh.V().row(mesh.E()(e, 0));
    const Eigen::Vector3d ne =
        (mesh.face_normals().row(mesh.EF()(e, 0)) + mesh.face_normals().row(mesh.EF()(e, 1))).normalized();
    const double scale = d.norm();
    ASSERT_LT((S - S.transpose()).norm(), 1e-14 * scale);
    ASSERT_LT((S * d).norm(), 1e-12 * scale * scale) << "edge " << e;
    ASSERT_LT((S * ne).norm(), 1e-12 * scale) << "edge " << e;
    ASSERT_NEAR(S.trace(), 2 * d.norm() * std::sin(0.5 * beta[e]), 1e-12 * scale);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(S);
    int nonzero = 0;
    for (int i = 0; i < 3; ++i) nonzero += std::abs(eig.eigenvalues()[i]) > 1e-12 * scale;
    ASSERT_LE(nonzero, 1);
  }
}

// On a convex surface with outward normals every turning angle is positive; Σ_e trace S(e) approximates
// ∫ 2H dA = 8π on the unit sphere (O(h²) error; h ≈ 0.05 here, so 1% is ample).
TEST(ShapeOperator, SphereSignAndTotalMeanCurvature) {
  const Mesh mesh = testing::make_ellipsoid(5);
  const Eigen::VectorXd beta = signed_dihedral_angles(mesh);
  EXPECT_GT(beta.minCoeff(), 0.0);
  double total = 0;
  for (int e = 0; e < mesh.num_edges(); ++e) total += edge_shape_operator(mesh, e).trace();
  EXPECT_NEAR(total, 8 * std::numbers::pi, 0.01 * 8 * std::numbers::pi);
}

// Interior vertices of a cylinder of radius r: S(p)/A_p ≈ (1/r) c cᵀ with c the circumferential direction.
TEST(ShapeOperator, CylinderVertexOperator) {
  const double r = 1.5;
  const Mesh mesh = testing::make_cylinder(48, 16, r, 3.0);
  const std::vector<Eigen::Matrix3d> S = vertex_shape_operators(mesh);
  Eigen::VectorXd A = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) A[mesh.F()(f, k)] += mesh.face_areas()[f] / 3;
  int checked = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (mesh.is_boundary_vertex(v)) continue;
    const Eigen::Vector3d p = mesh.V().row(v);
    const Eigen::Vector3d c = Eigen::Vector3d(-p.y(), p.x(), 0).normalized();
    const Eigen::Matrix3d expected = (1 / r) * c * c.transpose();
    // Chord-vs-arc and area discretization: relative error O((2π/48)²) ≈ 2%.
    EXPECT_LT((S[static_cast<std::size_t>(v)] / A[v] - expected).norm(), 0.03 / r) << "vertex " << v;
    ++checked;
  }
  EXPECT_EQ(checked, 48 * 15);
}

TEST(ShapeOperator, PlaneIsFlat) {
  const Mesh mesh = testing::make_grid(6);
  for (const auto& S : vertex_shape_operators(mesh)) EXPECT_LT(S.norm(), 1e-14);
  EXPECT_LT(signed_dihedral_angles(mesh).cwiseAbs().maxCoeff(), 1e-14);
}

}  // namespace
}  // namespace quadcover
