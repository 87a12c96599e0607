// Gradients of conforming and Crouzeix–Raviart functions (thesis 1.2), checked against direct recomputation from
// the geometry: linear functions, differences of values along edges, and the inclusion S_h ⊂ S_h* (1.4).
#include "calculus/gradient.h"

#include <gtest/gtest.h>

#include "calculus/stiffness.h"
#include "calculus_test_util.h"

namespace quadcover {
namespace {

using testing::cached_mesh;
using testing::random_vector;

class GradientOnRealMeshes : public ::testing::TestWithParam<const char*> {};

// ∇(a·x) on a face is the tangential part of a, written in the face basis.
TEST_P(GradientOnRealMeshes, LinearFunctionHasProjectedGradient) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::Vector3d a(0.3, -1.1, 0.7);
  const VectorField X = gradient(mesh, mesh.V() * a);
  for (int f = 0; f < mesh.num_faces(); ++f) ASSERT_LT(std::abs(X[f] - mesh.to_local(f, a)), 1e-9 * a.norm()) << f;
}

// ⟨∇u, p_j - p_i⟩ = u_j - u_i along each face edge, and ⟨∇v, m_a - m_b⟩ = v_a - v_b between edge midpoints.
TEST_P(GradientOnRealMeshes, GradientsReproduceDifferences) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::VectorXd u = random_vector(mesh.num_vertices(), 21), v = random_vector(mesh.num_edges(), 22);
  const VectorField Gu = gradient(mesh, u), Gv = nonconforming_gradient(mesh, v);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& P = mesh.corner_local();
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const Complex d = P(f, j) - P(f, i);
      ASSERT_NEAR((std::conj(Gu[f]) * d).real(), u[mesh.F()(f, j)] - u[mesh.F()(f, i)], 1e-9) << "face " << f;
      const Complex mi = 0.5 * (P(f, j) + P(f, k)), mj = 0.5 * (P(f, k) + P(f, i));  // midpoints of edges i, j
      ASSERT_NEAR((std::conj(Gv[f]) * (mj - mi)).real(), v[mesh.FE()(f, j)] - v[mesh.FE()(f, i)], 1e-9) << f;
    }
  }
}

// The sparse matrices act like the functions.
TEST_P(GradientOnRealMeshes, MatricesMatchFunctions) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::VectorXd u = random_vector(mesh.num_vertices(), 31), v = random_vector(mesh.num_edges(), 32);
  const VectorField a = conforming_gradient(mesh) * u.cast<Complex>(), b = gradient(mesh, u);
  const VectorField c = nonconforming_gradient(mesh) * v.cast<Complex>(), d = nonconforming_gradient(mesh, v);
  EXPECT_LT((a - b).norm(), 1e-12 * b.norm());
  EXPECT_LT((c - d).norm(), 1e-12 * d.norm());
}

// (1.4): φ_p = ½ Σ_{e∋p} ψ_e, so u ∈ S_h equals the CR function with midpoint values ½Cu, same gradient.
TEST_P(GradientOnRealMeshes, ConformingFunctionsAreNonconforming) {
  const Mesh& mesh = cached_mesh(GetParam());
  const Eigen::VectorXd u = random_vector(mesh.num_vertices(), 41);
  const Eigen::VectorXd midpoints = 0.5 * (edge_vertex_incidence(mesh) * u);
  const VectorField a = gradient(mesh, u), b = nonconforming_gradient(mesh, midpoints);
  EXPECT_LT((a - b).norm(), 1e-12 * a.norm());
}

INSTANTIATE_TEST_SUITE_P(Meshes, GradientOnRealMeshes, ::testing::ValuesIn(testing::kCalculusMeshes));

}  // namespace
}  // namespace quadcover
