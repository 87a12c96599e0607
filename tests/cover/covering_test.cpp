// The explicit covering M̃ (thesis 3.2.2): Lemma 3.5 on real meshes with generated fields, and (3.9).
#include "cover/covering.h"

#include <gtest/gtest.h>

#include <random>

#include "cover/complex_stiffness.h"
#include "cover/field_helpers.h"
#include "field/compute_frame_field.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

using testing::load_test_mesh;

// 4·ind_p (Def. 3.2, our sign): -Σ m over the edges crossed counter-clockwise around p; 0 on the boundary.
std::pair<int, int> count_branch_points(const Mesh& mesh, const Eigen::VectorXi& m) {
  int b_even = 0, b_odd = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (mesh.is_boundary_vertex(v)) continue;
    const auto fan = mesh.fan(v);
    int q = 0;
    for (std::size_t i = 0; i < fan.size(); ++i) {
      const int f = fan[i].face, g = fan[(i + 1) % fan.size()].face;
      for (int k = 0; k < 3; ++k)
        if (mesh.neighbor(f, k) == g) {
          const int e = mesh.FE()(f, k);
          q -= mesh.EF()(e, 0) == f ? m[e] : -m[e];
        }
    }
    const int r = ((q % 4) + 4) % 4;
    b_odd += (r == 1 || r == 3);
    b_even += (r == 2);
  }
  return {b_even, b_odd};
}

class ClosedMeshes : public ::testing::TestWithParam<const char*> {};

// Lemma 3.5 (4), b_odd > 0: M̃ is connected with genus 4g + b_even + 3/2 b_odd - 3 (Riemann–Hurwitz), for random
// matchings (many branch points, some adjacent), generated smooth fields and the curvature fields of Chapter 5.
TEST_P(ClosedMeshes, GenusWithOddBranchPoints) {
  const Mesh mesh = load_test_mesh(GetParam());
  const int g = mesh.genus();
  for (const FrameField& field : {testing::random_frame_field(mesh, 3), testing::random_cross_field(mesh, 8),
                                  testing::smooth_cross_field(mesh), compute_frame_field(mesh)}) {
    const auto [b_even, b_odd] = count_branch_points(mesh, field.matching);
    const Covering cov = build_covering(mesh, field.matching);
    int chi = 0;
    for (int c = 0; c < cov.num_components; ++c) chi += cov.euler_characteristic[c];
    EXPECT_EQ(chi, 4 * mesh.euler_characteristic() - 3 * b_odd - 2 * b_even);  // Riemann–Hurwitz
    EXPECT_EQ(cov.num_vertices(), 4 * mesh.num_vertices() - 3 * b_odd - 2 * b_even);
    if (b_odd == 0) {  // (the curvature field of the torus has no branch points at all: 1, 2 or 4 sheets' worth)
      EXPECT_EQ(4 % cov.num_components, 0);
      continue;
    }
    ASSERT_EQ(cov.num_components, 1);
    EXPECT_EQ(cov.genus()[0], expected_covering_genus(g, b_even, b_odd)) << b_even << " " << b_odd;
  }
}

// b_odd = 0 < b_even (even matchings 2k): two components of genus 2g + ½b_even - 1 each.
TEST_P(ClosedMeshes, TwoComponentsWithOnlyEvenBranchPoints) {
  const Mesh mesh = load_test_mesh(GetParam());
  Eigen::VectorXi m = 2 * testing::random_frame_field(mesh, 9).matching;
  const auto [b_even, b_odd] = count_branch_points(mesh, m);
  ASSERT_EQ(b_odd, 0);
  ASSERT_GT(b_even, 0);
  const Covering cov = build_covering(mesh, m);
  ASSERT_EQ(cov.num_components, 2);
  for (int c = 0; c < 2; ++c) EXPECT_EQ(cov.genus()[c], 2 * mesh.genus() + b_even / 2 - 1);
}

// No branch points and trivial holonomy: four copies of M.
TEST_P(ClosedMeshes, FourCopiesWithoutBranchPoints) {
  const Mesh mesh = load_test_mesh(GetParam());
  std::mt19937 rng(2);
  std::uniform_int_distribution<int> d(0, 3);
  Eigen::VectorXi r(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) r[f] = d(rng);
  const Covering cov = build_covering(mesh, testing::gauge_matching(mesh, r));
  ASSERT_EQ(cov.num_components, 4);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(cov.genus()[c], mesh.genus());
}

// Lemma 3.5 (1)-(2): with pairwise non-adjacent branch points, M̃ is an abstract simplicial surface — it passes the
// full mesh validation as a triangle mesh (manifold, no duplicate faces), with the predicted topology.
TEST_P(ClosedMeshes, CoveringWithIsolatedBranchPointsIsASimplicialSurface) {
  const Mesh mesh = load_test_mesh(GetParam());
  const int n = mesh.num_vertices();
  const std::vector<std::pair<int, int>> odd = {{n / 9, 5 * n / 9}, {2 * n / 9, 7 * n / 9}};
  const std::vector<std::pair<int, int>> even = {{3 * n / 9, 8 * n / 9}};
  Eigen::VectorXi m = testing::add_branch_pairs(mesh, Eigen::VectorXi::Zero(mesh.num_edges()), odd, 1);
  m = testing::add_branch_pairs(mesh, m, even, 2);
  const auto [b_even, b_odd] = count_branch_points(mesh, m);
  ASSERT_EQ(b_odd, 4);
  ASSERT_EQ(b_even, 2);
  const Covering cov = build_covering(mesh, m);
  const PolygonSoup soup = PolygonSoup::from_triangles(covering_positions(mesh, cov), cov.F);
  const ValidationReport report = validate(soup);
  for (const auto& p : report.problems) ADD_FAILURE() << p.message;
  ASSERT_TRUE(report.valid());
  const Mesh covering_mesh = build_mesh(soup).mesh;
  EXPECT_EQ(covering_mesh.num_components(), 1);
  EXPECT_EQ(covering_mesh.genus(), expected_covering_genus(mesh.genus(), b_even, b_odd));
  EXPECT_EQ(covering_mesh.num_edges(), 4 * mesh.num_edges());
}

// (3.9): 𝔏̄* acting on complex functions equals the real block matrix 𝔏̃* (3.7) of the explicit covering acting on
// the symmetric functions ũ_{4e+r} = Re(i^{-r} ū_e), and ūᴴ𝔏̄*ū = ½ ũᵀ𝔏̃*ũ.
TEST_P(ClosedMeshes, ComplexStiffnessActsLikeCoveringStiffness) {
  const Mesh mesh = load_test_mesh(GetParam());
  const FrameField field = testing::random_frame_field(mesh, 21);
  const Covering cov = build_covering(mesh, field.matching);
  const Eigen::SparseMatrix<double> Lt = covering_nonconforming_stiffness(mesh, cov);
  const Eigen::SparseMatrix<Complex> Lc = complex_nonconforming_stiffness(mesh, field.matching);
  std::mt19937 rng(1);
  std::normal_distribution<double> g(0, 1);
  Eigen::VectorXcd u(mesh.num_edges());
  for (int e = 0; e < mesh.num_edges(); ++e) u[e] = Complex(g(rng), g(rng));
  auto lift = [&](const Eigen::VectorXcd& w) {
    Eigen::VectorXd out(4 * mesh.num_edges());
    for (int e = 0; e < mesh.num_edges(); ++e)
      for (int r = 0; r < 4; ++r) out[4 * e + r] = std::real(ipow(-r) * w[e]);
    return out;
  };
  const Eigen::VectorXd ut = lift(u);
  const Eigen::VectorXd lhs = Lt * ut, rhs = lift(Lc * u);
  EXPECT_LT((lhs - rhs).norm(), 1e-10 * lhs.norm());
  EXPECT_NEAR(0.5 * ut.dot(Lt * ut), u.dot(Lc * u).real(), 1e-9 * ut.dot(Lt * ut));
}

INSTANTIATE_TEST_SUITE_P(Meshes, ClosedMeshes,
                         ::testing::Values("bunny_3k", "torus_5k", "eight_genus2", "3holes_genus3",
                                           "fertility_genus4"));

// With boundary: χ(M̃) = 4χ(M) - 3 b_odd - 2 b_even still holds (boundary vertices have index 0), and every
// boundary loop of M lifts to boundary loops of M̃ covering it four times.
TEST(CoveringWithBoundary, RiemannHurwitzAndBoundaryLift) {
  for (const char* name : {"lilium_disk", "mech_holes_shark"}) {
    const Mesh mesh = load_test_mesh(name);
    const FrameField field = testing::random_cross_field(mesh, 4);
    const auto [b_even, b_odd] = count_branch_points(mesh, field.matching);
    const Covering cov = build_covering(mesh, field.matching);
    int chi = 0, loops = 0;
    for (int c = 0; c < cov.num_components; ++c) {
      chi += cov.euler_characteristic[c];
      loops += cov.boundary_loops[c];
    }
    EXPECT_EQ(chi, 4 * mesh.euler_characteristic() - 3 * b_odd - 2 * b_even) << name;
    EXPECT_GE(loops, mesh.num_boundary_loops()) << name;
    EXPECT_LE(loops, 4 * mesh.num_boundary_loops()) << name;
  }
}

}  // namespace
}  // namespace quadcover
