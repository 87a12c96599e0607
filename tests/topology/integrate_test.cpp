// Integration over the cut disk (thesis (1.11)-(1.12)).
#include "topology/integrate.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "calculus/gradient.h"
#include "calculus/hodge.h"
#include "support/test_meshes.h"
#include "topology/base_sets.h"
#include "topology/cut_graph.h"
#include "topology/harmonic_basis.h"

namespace quadcover {
namespace {

Eigen::VectorXd random_function(const Mesh& mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unif(-1, 1);
  Eigen::VectorXd u(mesh.num_vertices());
  for (int v = 0; v < u.size(); ++v) u[v] = unif(rng);
  return u;
}

// Gradient of the per-corner values of face f: Σ_c φ_c ∇φ_c, ∇φ_c = (1/2A) J e_c.
Complex corner_gradient(const Mesh& mesh, const Eigen::MatrixX3d& phi, int f) {
  Complex g = 0;
  for (int c = 0; c < 3; ++c)
    g += phi(f, c) * Complex(0, 1) * mesh.edge_vector_local(f, c) / (2 * mesh.face_areas()[f]);
  return g;
}

class IntegrateOnMeshes : public ::testing::TestWithParam<std::string> {};

// (1.11): integrating ∇u of a random u on the cut disk recovers u up to one constant.
TEST_P(IntegrateOnMeshes, RecoversFunctionFromItsGradient) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  const auto base = testing::random_interior_vertices(mesh, 4, 3);
  const CutGraph g = cut_graph(mesh, base);
  const CutMesh cut = cut_mesh(mesh, g.cut);
  const Eigen::VectorXd u = random_function(mesh, 5);
  const Eigen::MatrixX3d phi = integrate(mesh, cut, gradient(mesh, u));
  const double offset = phi(0, 0) - u[mesh.F()(0, 0)];
  double worst = 0;
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(phi(f, k) - u[mesh.F()(f, k)] - offset));
  EXPECT_LE(worst, 1e-9);
}

// A harmonic field with non-zero periods is integrable on the cut disk only: ∇φ = H on every face, and φ jumps
// across the cut edges by constants (here: the jump across the crossing edge of generator j is its period).
TEST_P(IntegrateOnMeshes, IntegratesHarmonicFieldsOnTheDisk) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  const CutGraph g = cut_graph(mesh);
  const CutMesh cut = cut_mesh(mesh, g.cut);
  const HomologyBasis basis = homology_basis(mesh, g);
  ASSERT_GT(basis.size(), 0);
  const HodgeDecomposer hodge(mesh);
  Eigen::VectorXd b(basis.size());
  for (int j = 0; j < b.size(); ++j) b[j] = 1.0 + j;
  const VectorField H = harmonic_field_with_periods(hodge, basis, sigma_fields(mesh, basis), b);
  const Eigen::MatrixX3d phi = integrate(mesh, cut, H);
  double worst = 0, scale = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    worst = std::max(worst, std::abs(corner_gradient(mesh, phi, f) - H[f]));
    scale = std::max(scale, std::abs(H[f]));
  }
  EXPECT_LE(worst, 1e-8 * scale);
  // Jump across e_j: value of φ at an endpoint seen from the left face minus from the right face = b_j (1.11).
  for (int j = 0; j < basis.size(); ++j) {
    const int e = basis.generators[j].crossing_edge;
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1), p = mesh.E()(e, 0);
    auto value = [&](int f) {
      for (int k = 0; k < 3; ++k)
        if (mesh.F()(f, k) == p) return phi(f, k);
      return 0.0;
    };
    // γ_j* crosses e_j from its left face to its right face, so ∫ along it = φ_left - φ_right at e_j = b_j.
    const auto& gen = basis.generators[j];
    std::size_t at = 0;
    while (gen.edges[at] != e) ++at;
    const bool positive = gen.vertices[at] == mesh.E()(e, 0);
    const double jump = positive ? value(s) - value(t) : value(t) - value(s);
    EXPECT_NEAR(jump, b[j], 1e-8 * b.maxCoeff()) << "generator " << j;
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, IntegrateOnMeshes,
                         ::testing::Values("torus_5k", "eight_genus2", "fertility_genus4", "couplingdown_genus9",
                                           "mech_holes_shark"));

// φ = φ⁰ + iφ¹ of a gradient frame (∇u₀, ∇u₁) is u₀ + iu₁ up to a constant, also on a sphere cut at base vertices.
TEST(Integrate, FrameOfGradients) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const CutGraph g = cut_graph(mesh, std::vector<int>{10, 500, 1500});
  const CutMesh cut = cut_mesh(mesh, g.cut);
  const Eigen::VectorXd u0 = random_function(mesh, 8), u1 = random_function(mesh, 9);
  const Eigen::MatrixX3cd phi = integrate_frame(mesh, cut, gradient(mesh, u0), gradient(mesh, u1));
  const Complex offset = phi(0, 0) - Complex(u0[mesh.F()(0, 0)], u1[mesh.F()(0, 0)]);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F()(f, k);
      EXPECT_LE(std::abs(phi(f, k) - Complex(u0[v], u1[v]) - offset), 1e-9);
    }
}

// A closed sphere needs no cut (simply connected): integrating ∇u over the uncut mesh gives u up to a constant.
TEST(Integrate, UncutSphere) {
  const Mesh mesh = testing::load_test_mesh("spot");
  const CutGraph g = cut_graph(mesh);
  ASSERT_EQ(g.paths.size(), 0u);
  const CutMesh cut = cut_mesh(mesh, g.cut);
  EXPECT_EQ(cut.num_vertices(), mesh.num_vertices());
  const Eigen::VectorXd u = random_function(mesh, 11);
  const Eigen::VectorXd w = integrate_cut_vertices(mesh, cut, gradient(mesh, u));
  const double offset = w[cut.corner_vertex(0, 0)] - u[mesh.F()(0, 0)];
  for (int v = 0; v < cut.num_vertices(); ++v) EXPECT_NEAR(w[v] - u[cut.original_vertex[v]], offset, 1e-9);
}

}  // namespace
}  // namespace quadcover
