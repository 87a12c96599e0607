// Discrete divergence and curl (Def. 1.11, (1.6), (1.7)) on real meshes with and without boundary: per-edge
// formulas, the weak form against the gradients, the averaging property, and the complex identities
// curl* ∇u = 0 (interior edges) and div J∇v = 0 (v ∈ S_h* vanishing on boundary edges).
#include "calculus/div_curl.h"

#include <gtest/gtest.h>

#include "calculus/gradient.h"
#include "calculus/stiffness.h"
#include "calculus_test_util.h"

namespace quadcover {
namespace {

using testing::cached_mesh;
using testing::random_field;
using testing::random_vector;

const Complex kJ{0, 1};
double dot(Complex a, Complex b) { return (std::conj(a) * b).real(); }

class DivCurlOnRealMeshes : public ::testing::TestWithParam<const char*> {};

// Per edge with s = EF(e,0), t = EF(e,1) and e expressed in each face's basis: div* = ⟨X_s - X_t, Je⟩ (1.6) and
// curl* = ⟨X_t - X_s, e⟩ (Def. 1.11 and (3.3); see div_curl.h for the sign); missing faces contribute nothing.
TEST_P(DivCurlOnRealMeshes, StarOperatorsMatchEdgeFormulas) {
  const Mesh& mesh = cached_mesh(GetParam());
  const VectorField X = random_field(mesh, 51);
  const Eigen::VectorXd ds = divergence_star(mesh, X), cs = curl_star(mesh, X);
  for (int e = 0; e < mesh.num_edges(); ++e) {
    double div = 0, curl = 0;
    if (const int s = mesh.EF()(e, 0); s >= 0) {
      const Complex es = mesh.edge_vector_local(s, mesh.EF_corner()(e, 0));  // E0 -> E1 in s's basis
      div += dot(X[s], kJ * es);
      curl -= dot(X[s], es);
    }
    if (const int t = mesh.EF()(e, 1); t >= 0) {
      const Complex et = -mesh.edge_vector_local(t, mesh.EF_corner()(e, 1));  // E0 -> E1 in t's basis
      div -= dot(X[t], kJ * et);
      curl += dot(X[t], et);
    }
    ASSERT_NEAR(ds[e], div, 1e-12 * (1 + std::abs(div))) << "edge " << e;
    ASSERT_NEAR(cs[e], curl, 1e-12 * (1 + std::abs(curl))) << "edge " << e;
  }
}

// Weak forms: div X(p) = -∫⟨X, ∇φ_p⟩, div* X(e) = -∫⟨X, ∇ψ_e⟩ (proof of (1.8)), i.e. -Re(Gᴴ diag(A) X).
TEST_P(DivCurlOnRealMeshes, DivergenceIsMinusAdjointGradient) {
  const Mesh& mesh = cached_mesh(GetParam());
  const VectorField X = random_field(mesh, 52);
  const Eigen::VectorXcd AX = mesh.face_areas().cast<Complex>().cwiseProduct(X);
  const Eigen::VectorXd weak = -(conforming_gradient(mesh).adjoint() * AX).real();
  const Eigen::VectorXd weak_star = -(nonconforming_gradient(mesh).adjoint() * AX).real();
  const Eigen::VectorXd d = divergence(mesh, X), ds = divergence_star(mesh, X);
  EXPECT_LT((d - weak).norm(), 1e-12 * weak.norm());
  EXPECT_LT((ds - weak_star).norm(), 1e-12 * weak_star.norm());
}

// (1.7): div = ½ Cᵀ div*, curl = ½ Cᵀ curl*; and (1.6): curl = -div J, curl* = -div* J.
TEST_P(DivCurlOnRealMeshes, AveragingPropertyAndRotation) {
  const Mesh& mesh = cached_mesh(GetParam());
  const VectorField X = random_field(mesh, 53);
  const Eigen::SparseMatrix<double> Ct = edge_vertex_incidence(mesh).transpose();
  const Eigen::VectorXd d = divergence(mesh, X), c = curl(mesh, X);
  EXPECT_LT((d - 0.5 * Ct * divergence_star(mesh, X)).norm(), 1e-12 * d.norm());
  EXPECT_LT((c - 0.5 * Ct * curl_star(mesh, X)).norm(), 1e-12 * c.norm());
  const VectorField JX = kJ * X;
  EXPECT_LT((c + divergence(mesh, JX)).norm(), 1e-12 * c.norm());
  EXPECT_LT((curl_star(mesh, X) + divergence_star(mesh, JX)).norm(), 1e-12 * c.norm());
  // Gauss: the vertex divergences of any field sum to zero (Σ_p φ_p = 1).
  EXPECT_NEAR(d.sum(), 0.0, 1e-10 * d.lpNorm<1>());
}

// curl* ∇u = 0 on every interior edge; on a boundary edge only the face's own edge term -⟨∇u, e_f⟩ remains.
TEST_P(DivCurlOnRealMeshes, GradientsAreCurlFree) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::VectorXd u = random_vector(mesh.num_vertices(), 54);
  const VectorField G = gradient(mesh, u);
  const Eigen::VectorXd cs = curl_star(mesh, G), c = curl(mesh, G);
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (!mesh.is_boundary_edge(e)) {
      ASSERT_NEAR(cs[e], 0.0, 1e-10) << "edge " << e;
    } else {
      const int side = mesh.EF()(e, 0) >= 0 ? 0 : 1;  // the face traverses E0 -> E1 iff side 0
      const double du = u[mesh.E()(e, 1)] - u[mesh.E()(e, 0)];
      ASSERT_NEAR(cs[e], side == 0 ? -du : du, 1e-10) << "boundary edge " << e;
    }
  }
  for (int p = 0; p < mesh.num_vertices(); ++p)
    if (!mesh.is_boundary_vertex(p)) {
      ASSERT_NEAR(c[p], 0.0, 1e-10) << "vertex " << p;
    }
}

// div J∇v = 0 at every interior vertex for v ∈ S_h*, and everywhere when v vanishes on boundary edges.
TEST_P(DivCurlOnRealMeshes, RotatedNonconformingGradientsAreDivergenceFree) {
  const Mesh& mesh = cached_mesh(GetParam());
  Eigen::VectorXd v = random_vector(mesh.num_edges(), 55);
  Eigen::VectorXd d = divergence(mesh, kJ * nonconforming_gradient(mesh, v));
  bool boundary_nonzero = false;
  for (int p = 0; p < mesh.num_vertices(); ++p) {
    if (!mesh.is_boundary_vertex(p)) {
      ASSERT_NEAR(d[p], 0.0, 1e-10) << "vertex " << p;
    } else {
      boundary_nonzero |= std::abs(d[p]) > 1e-3;
    }
  }
  EXPECT_EQ(boundary_nonzero, mesh.num_boundary_loops() > 0);  // the boundary term is real, not an artifact
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (mesh.is_boundary_edge(e)) v[e] = 0;
  d = divergence(mesh, kJ * nonconforming_gradient(mesh, v));
  EXPECT_LT(d.lpNorm<Eigen::Infinity>(), 1e-10);
}

INSTANTIATE_TEST_SUITE_P(Meshes, DivCurlOnRealMeshes, ::testing::ValuesIn(testing::kCalculusMeshes));

}  // namespace
}  // namespace quadcover
