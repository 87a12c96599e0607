// The power-field fill (field/power_field.h): a minimizer, exact at held faces, equivariant, the
// Ginzburg–Landau steps descend, and a field with nothing to follow but one face is parallel.
#include "field/power_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "field/indices.h"
#include "field/matching.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// A problem on a real mesh: curvature-like noisy targets, weights on every third face, some faces held.
PowerFieldProblem noisy_problem(const Mesh& mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), unit(0.0, 1.0);
  PowerFieldProblem p;
  const int nf = mesh.num_faces();
  p.target.resize(nf);
  p.weight = Eigen::VectorXd::Zero(nf);
  p.fixed.assign(static_cast<std::size_t>(nf), 0);
  for (int t = 0; t < nf; ++t) {
    p.target[t] = std::polar(0.5 + unit(rng), angle(rng));
    if (t % 3 == 0) p.weight[t] = 2 * unit(rng);
    if (t % 97 == 5) p.fixed[static_cast<std::size_t>(t)] = 1;
  }
  return p;
}

// ∇E = 0 at the linear solution: for random complex directions v on the free faces the first-order change of
// E, (E(u+εv) - E(u-εv)) / 2ε, vanishes while the second-order one does not.
TEST(PowerField, LinearSolutionIsTheMinimizer) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const PowerFieldProblem p = noisy_problem(mesh, 7);
  const PowerFieldResult r = smooth_power_field(mesh, p);
  EXPECT_EQ(r.iterations, 0);
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  const double E0 = power_field_energy(mesh, p, r.u), eps = 1e-3;
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXcd v = Eigen::VectorXcd::Zero(mesh.num_faces());
    for (int t = 0; t < mesh.num_faces(); ++t)
      if (!r.held[static_cast<std::size_t>(t)]) v[t] = Complex(g(rng), g(rng));
    const double plus = power_field_energy(mesh, p, r.u + eps * v);
    const double minus = power_field_energy(mesh, p, r.u - eps * v);
    const double first = (plus - minus) / (2 * eps), second = (plus + minus - 2 * E0) / (eps * eps);
    EXPECT_GT(second, 0);
    EXPECT_LT(std::abs(first), 1e-7 * second) << "trial " << trial;
  }
}

// Held faces keep u_t = c_t and X_t = d_t/|d_t| exactly; elsewhere X_t^4 has the direction of u_t.
TEST(PowerField, HeldFacesExactAndRootsConsistent) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  PowerFieldProblem p = noisy_problem(mesh, 11);
  p.unit_weight = 1000;
  p.iterations = 5;
  const PowerFieldResult r = smooth_power_field(mesh, p);
  EXPECT_GT(r.iterations, 0);
  for (int t = 0; t < mesh.num_faces(); ++t) {
    ASSERT_NEAR(std::abs(r.X[t]), 1.0, 1e-14);
    if (p.fixed[static_cast<std::size_t>(t)]) {
      EXPECT_EQ(r.X[t], p.target[t] / std::abs(p.target[t]));
      EXPECT_NEAR(std::abs(r.u[t] - std::pow(p.target[t] / std::abs(p.target[t]), 4)), 0.0, 1e-14);
    } else if (std::abs(r.u[t]) > 1e-9) {
      EXPECT_NEAR(std::abs(std::pow(r.X[t], 4) - r.u[t] / std::abs(r.u[t])), 0.0, 1e-12) << t;
    }
  }
}

// Rotating every target by the same angle φ in its face rotates u by 4φ: E is invariant under u ↦ e^{4iφ}u.
TEST(PowerField, RotationEquivariance) {
  const Mesh mesh = testing::load_test_mesh("torus_5k");
  PowerFieldProblem p = noisy_problem(mesh, 5);
  p.unit_weight = 300;
  p.iterations = 3;
  const PowerFieldResult a = smooth_power_field(mesh, p);
  const Complex turn = std::polar(1.0, 0.3);
  p.target *= turn;
  const PowerFieldResult b = smooth_power_field(mesh, p);
  EXPECT_LT((b.u - std::pow(turn, 4) * a.u).cwiseAbs().maxCoeff(), 1e-9);
}

// Majorize-minimize: every step lowers E(u) + σ Σ (A_t/A_M)(|u_t| - 1)² (or keeps it).
TEST(PowerField, GinzburgLandauStepsDescend) {
  const Mesh mesh = testing::load_test_mesh("eight_genus2");
  PowerFieldProblem p = noisy_problem(mesh, 13);
  p.unit_weight = 1000;
  double previous = INFINITY;
  for (int k = 0; k <= 6; ++k) {
    p.iterations = k;
    const PowerFieldResult r = smooth_power_field(mesh, p);
    const double E = power_field_energy(mesh, p, r.u, true);
    EXPECT_LE(E, previous * (1 + 1e-12)) << "step " << k;
    if (k == 1) {  // the first step makes real progress from the linear solution
      EXPECT_LT(E, 0.99 * previous);
    }
    previous = E;
  }
}

// On a flat grid with zero weights and one held face, the minimizer is the parallel field (E = 0): every face
// carries the same world cross and there is no branch point.
TEST(PowerField, FlatGridWithOneHeldFaceIsParallel) {
  const Mesh mesh = testing::make_grid(12);
  const int nf = mesh.num_faces();
  const Eigen::Vector3d w = Eigen::Vector3d(2, 1, 0).normalized();
  PowerFieldProblem p;
  p.target.resize(nf);
  for (int t = 0; t < nf; ++t) p.target[t] = mesh.to_local(t, Eigen::Vector3d(0, 1, 0));  // ignored: weight 0
  p.target[17] = mesh.to_local(17, w);
  p.weight = Eigen::VectorXd::Zero(nf);
  p.fixed.assign(static_cast<std::size_t>(nf), 0);
  p.fixed[17] = 1;
  const PowerFieldResult r = smooth_power_field(mesh, p);
  EXPECT_LT(power_field_energy(mesh, p, r.u), 1e-20);
  for (int t = 0; t < nf; ++t) {
    const Eigen::Vector3d u = mesh.to_world(t, r.X[t]);
    EXPECT_LT(std::min(u.cross(w).norm(), std::abs(u.dot(w))), 1e-9) << t;  // u ∥ w or u ⟂ w
  }
  EXPECT_TRUE(branch_points(mesh, cross_field_with_straightest_matching(mesh, r.X)).empty());
}

// A component with neither weights nor held faces gets its lowest face held; wrong inputs are rejected.
TEST(PowerField, AnchoringAndInputChecks) {
  const Mesh mesh = testing::load_test_mesh("torus_5k");
  PowerFieldProblem p;
  p.target = Eigen::VectorXcd::Constant(mesh.num_faces(), Complex(1, 0));
  p.weight = Eigen::VectorXd::Zero(mesh.num_faces());
  const PowerFieldResult r = smooth_power_field(mesh, p);
  EXPECT_EQ(std::count(r.held.begin(), r.held.end(), 1), 1);
  EXPECT_EQ(r.held[0], 1);
  p.weight[3] = -1;
  EXPECT_THROW(smooth_power_field(mesh, p), std::invalid_argument);
  p.weight[3] = 0;
  p.alignment = -1;
  EXPECT_THROW(smooth_power_field(mesh, p), std::invalid_argument);
  p.alignment = 1;
  p.target.resize(5);
  EXPECT_THROW(smooth_power_field(mesh, p), std::invalid_argument);
}

}  // namespace
}  // namespace quadcover
