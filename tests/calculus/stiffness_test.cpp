// Stiffness matrices 𝔏, 𝔏* and the incidence C (thesis 1.2.1) on real meshes of genus 0-4 with and without
// boundary: identities that break if either matrix, the incidence or the gradients are wrong.
#include "calculus/stiffness.h"

#include <gtest/gtest.h>

#include "calculus/gradient.h"
#include "calculus_test_util.h"

namespace quadcover {
namespace {

using testing::cached_mesh;
using testing::random_vector;

class StiffnessOnRealMeshes : public ::testing::TestWithParam<const char*> {};

// 𝔏 = ¼ Cᵀ 𝔏* C (end of 1.2.1).
TEST_P(StiffnessOnRealMeshes, ConformingIsAveragedNonconforming) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::SparseMatrix<double> C = edge_vertex_incidence(mesh);
  const Eigen::SparseMatrix<double> expected = 0.25 * C.transpose() * nonconforming_stiffness(mesh) * C;
  const Eigen::SparseMatrix<double> L = conforming_stiffness(mesh);
  EXPECT_LT((L - expected).norm(), 1e-12 * expected.norm());
}

// 𝔏_pq = -½(cot α_pq + cot β_pq) from the mesh's corner cotangents, 𝔏_pp = -Σ_q 𝔏_pq.
TEST_P(StiffnessOnRealMeshes, ConformingMatchesCotanFormula) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::SparseMatrix<double> L = conforming_stiffness(mesh);
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (int e = 0; e < mesh.num_edges(); ++e) {
    double expected = 0;
    for (int side = 0; side < 2; ++side)
      if (mesh.EF()(e, side) >= 0)
        expected -= 0.5 * mesh.corner_cotangents()(mesh.EF()(e, side), mesh.EF_corner()(e, side));
    const int p = mesh.E()(e, 0), q = mesh.E()(e, 1);
    ASSERT_NEAR(L.coeff(p, q), expected, 1e-10 * (1 + std::abs(expected))) << "edge " << e;
    ASSERT_NEAR(L.coeff(q, p), expected, 1e-10 * (1 + std::abs(expected))) << "edge " << e;
    diagonal[p] -= expected;
    diagonal[q] -= expected;
  }
  for (int p = 0; p < mesh.num_vertices(); ++p) ASSERT_NEAR(L.coeff(p, p), diagonal[p], 1e-9 * (1 + diagonal[p]));
  EXPECT_EQ(L.nonZeros(), mesh.num_vertices() + 2 * mesh.num_edges());
}

// (1.5): 𝔏*_ef = -2 cot ∠(e,f) for the two edges meeting at each corner; every row sums to zero.
TEST_P(StiffnessOnRealMeshes, NonconformingMatchesAngleFormula) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::SparseMatrix<double> Ls = nonconforming_stiffness(mesh);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int e = mesh.FE()(f, (k + 1) % 3), g = mesh.FE()(f, (k + 2) % 3);
      const double expected = -2.0 / std::tan(mesh.corner_angles()(f, k));
      ASSERT_NEAR(Ls.coeff(e, g), expected, 1e-9 * (1 + std::abs(expected))) << "face " << f << " corner " << k;
    }
  const Eigen::VectorXd row_sums = Ls * Eigen::VectorXd::Ones(mesh.num_edges());
  EXPECT_LT(row_sums.lpNorm<Eigen::Infinity>(), 1e-10 * Ls.diagonal().maxCoeff());
}

// 𝔏 = Gᴴ diag(A) G and 𝔏* = G*ᴴ diag(A) G* (real parts): the stiffness entries are ∫⟨∇φ_p, ∇φ_q⟩.
TEST_P(StiffnessOnRealMeshes, StiffnessFromGradients) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::VectorXcd A = mesh.face_areas().cast<Complex>();
  const Eigen::SparseMatrix<Complex> G = conforming_gradient(mesh), Gs = nonconforming_gradient(mesh);
  const Eigen::SparseMatrix<double> L = conforming_stiffness(mesh), Ls = nonconforming_stiffness(mesh);
  const Eigen::SparseMatrix<Complex> AG = A.asDiagonal() * G, AGs = A.asDiagonal() * Gs;
  const Eigen::SparseMatrix<Complex> GAG = G.adjoint() * AG, GsAGs = Gs.adjoint() * AGs;
  EXPECT_LT((Eigen::SparseMatrix<double>(GAG.real()) - L).norm(), 1e-12 * L.norm());
  EXPECT_LT((Eigen::SparseMatrix<double>(GsAGs.real()) - Ls).norm(), 1e-12 * Ls.norm());
}

// E_D(u) = ½uᵀ𝔏u = -½ Σ_{pq ∈ E} 𝔏_pq (u_p - u_q)² (Def. 1.9) and the constants span the kernel.
TEST_P(StiffnessOnRealMeshes, DirichletEnergyAndKernel) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::SparseMatrix<double> L = conforming_stiffness(mesh), Ls = nonconforming_stiffness(mesh);
  const Eigen::VectorXd u = random_vector(mesh.num_vertices(), 11);
  double edge_sum = 0;
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int p = mesh.E()(e, 0), q = mesh.E()(e, 1);
    edge_sum += L.coeff(p, q) * (u[p] - u[q]) * (u[p] - u[q]);
  }
  const double energy = 0.5 * u.dot(L * u);
  EXPECT_GT(energy, 0);
  EXPECT_NEAR(energy, -0.5 * edge_sum, 1e-10 * energy);
  EXPECT_LT((L * Eigen::VectorXd::Ones(mesh.num_vertices())).lpNorm<Eigen::Infinity>(),
            1e-10 * L.diagonal().maxCoeff());
  EXPECT_LT((Ls * Eigen::VectorXd::Ones(mesh.num_edges())).lpNorm<Eigen::Infinity>(), 1e-10 * Ls.diagonal().maxCoeff());
}

// ∫u dA for u ∈ S_h is Σ_t A_t · mean of u at t's corners; ∫v for v ∈ S_h* is Σ_t A_t · mean at the midpoints.
TEST_P(StiffnessOnRealMeshes, AreasIntegratePiecewiseLinearFunctions) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::VectorXd u = random_vector(mesh.num_vertices(), 3), v = random_vector(mesh.num_edges(), 4);
  double iu = 0, iv = 0;
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      iu += mesh.face_areas()[f] * u[mesh.F()(f, k)] / 3.0;
      iv += mesh.face_areas()[f] * v[mesh.FE()(f, k)] / 3.0;
    }
  EXPECT_NEAR(vertex_areas(mesh).dot(u), iu, 1e-12 * mesh.total_area());
  EXPECT_NEAR(edge_areas(mesh).dot(v), iv, 1e-12 * mesh.total_area());
  EXPECT_NEAR(vertex_areas(mesh).sum(), mesh.total_area(), 1e-12 * mesh.total_area());
  EXPECT_NEAR(edge_areas(mesh).sum(), mesh.total_area(), 1e-12 * mesh.total_area());
}

// C is the edge graph's incidence: two ones per edge, and column sums are the vertex valences.
TEST_P(StiffnessOnRealMeshes, IncidenceCountsValences) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::SparseMatrix<double> C = edge_vertex_incidence(mesh);
  ASSERT_EQ(C.rows(), mesh.num_edges());
  ASSERT_EQ(C.cols(), mesh.num_vertices());
  EXPECT_TRUE(((C * Eigen::VectorXd::Ones(mesh.num_vertices())).array() == 2.0).all());
  const Eigen::VectorXd valence = C.transpose() * Eigen::VectorXd::Ones(mesh.num_edges());
  for (int p = 0; p < mesh.num_vertices(); ++p) ASSERT_EQ(valence[p], mesh.valence(p)) << "vertex " << p;
}

INSTANTIATE_TEST_SUITE_P(Meshes, StiffnessOnRealMeshes, ::testing::ValuesIn(testing::kCalculusMeshes));

// Linear precision (1.2.1): on a planar mesh 𝔏 annihilates linear functions at every interior vertex.
TEST(Stiffness, LinearPrecisionOnPlanarGrid) {
  const Mesh mesh = testing::make_grid(9);
  const Eigen::SparseMatrix<double> L = conforming_stiffness(mesh);
  const Eigen::VectorXd u = 0.3 * mesh.V().col(0) - 1.7 * mesh.V().col(1);
  const Eigen::VectorXd Lu = L * u;
  int interior = 0;
  for (int p = 0; p < mesh.num_vertices(); ++p)
    if (!mesh.is_boundary_vertex(p)) {
      ++interior;
      EXPECT_NEAR(Lu[p], 0.0, 1e-12) << "vertex " << p;
    }
  EXPECT_EQ(interior, 8 * 8);
  // ... but not at the boundary, where the natural boundary term remains.
  EXPECT_GT(Lu.lpNorm<Eigen::Infinity>(), 0.1);
}

}  // namespace
}  // namespace quadcover
