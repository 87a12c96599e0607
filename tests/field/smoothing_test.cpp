// Smoothing (thesis 5.2.1, (5.3)-(5.4)) and re-solves after matching changes (5.2.2).
#include "field/smoothing.h"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "field/matching.h"
#include "field/propagation.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// The propagated curvature field of a real mesh, as compute_frame_field builds it before smoothing.
struct Propagated {
  Mesh mesh;
  FrameField field;
  Eigen::VectorXd stability;
  std::vector<char> trusted;
};
Propagated propagated(const std::string& name) {
  Propagated s{testing::load_test_mesh(name), {}, {}, {}};
  const CurvatureFrames frames = principal_curvature_frames(s.mesh);
  const Eigen::VectorXd theta =
      field_curvature(s.mesh, cross_field_with_straightest_matching(s.mesh, frames.direction));
  s.stability = stability_weights(s.mesh, frames, theta);
  s.trusted = select_trusted(s.mesh, s.stability, 0.2);
  s.field =
      cross_field_with_straightest_matching(s.mesh, propagate_frames(s.mesh, frames.direction, s.trusted, s.stability));
  return s;
}

// For minimizers α(λ) of λE_S + (1-λ)E_A, E_S is non-increasing and E_A non-decreasing in λ.
TEST(Smoothing, SmoothingEnergyDecreasesWithLambda) {
  const Propagated s = propagated("bunny_3k");
  double last_S = std::numeric_limits<double>::infinity(), last_A = -1;
  const double initial = FrameSmoother(s.mesh, s.field, s.stability, s.trusted, {}, 0.5)
                             .smoothing_energy(Eigen::VectorXd::Zero(s.mesh.num_faces()));
  for (double lambda : {0.02, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 1.0}) {
    const FrameSmoother smoother(s.mesh, s.field, s.stability, s.trusted, {}, lambda);
    const Eigen::VectorXd alpha = smoother.solve();
    const double ES = smoother.smoothing_energy(alpha), EA = smoother.alignment_energy(alpha);
    EXPECT_LE(ES, last_S * (1 + 1e-12)) << "λ = " << lambda;
    EXPECT_GE(EA, last_A * (1 - 1e-12)) << "λ = " << lambda;
    EXPECT_LT(ES, initial);
    last_S = ES;
    last_A = EA;
  }
}

// The solution minimizes (5.3): random perturbations of α never lower λE_S + (1-λ)E_A, and the energy
// evaluated through the rotated field (recomputing θ from the frames) equals the smoother's own E_S.
TEST(Smoothing, SolutionIsTheMinimizer) {
  const Propagated s = propagated("torus_5k");
  const double lambda = 0.6;
  const FrameSmoother smoother(s.mesh, s.field, s.stability, s.trusted, {}, lambda);
  const Eigen::VectorXd alpha = smoother.solve();
  const auto E = [&](const Eigen::VectorXd& a) {
    return lambda * smoother.smoothing_energy(a) + (1 - lambda) * smoother.alignment_energy(a);
  };
  const double best = E(alpha);
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd d(s.mesh.num_faces());
    for (int t = 0; t < d.size(); ++t) d[t] = normal(rng);
    EXPECT_GT(E(alpha + 1e-3 * d), best);
  }
  EXPECT_NEAR(smoothing_energy(s.mesh, smoother.rotated(alpha)), smoother.smoothing_energy(alpha),
              1e-9 * smoother.smoothing_energy(alpha));
}

// 5.2.2: after changing matchings, re-solving with the stored factorization equals a fresh solve of a smoother
// built from the changed matching.
TEST(Smoothing, ResolveAfterMatchingChangeEqualsFreshSolve) {
  const Propagated s = propagated("fertility_genus4");
  FrameSmoother smoother(s.mesh, s.field, s.stability, s.trusted, {}, 0.5);
  const Eigen::VectorXd before = smoother.solve();
  FrameField changed = s.field;
  std::mt19937 rng(9);
  for (int i = 0; i < 25; ++i) {
    const int e = static_cast<int>(rng() % static_cast<unsigned>(s.mesh.num_edges()));
    const int k = static_cast<int>(rng() % 7) - 3;
    smoother.change_matching(e, k);
    changed.matching[e] += k;
  }
  ASSERT_EQ(smoother.matching(), changed.matching);
  const Eigen::VectorXd resolved = smoother.solve();
  const FrameSmoother fresh(s.mesh, changed, s.stability, s.trusted, {}, 0.5);
  const Eigen::VectorXd direct = fresh.solve();
  EXPECT_GT((resolved - before).norm(), 1e-3);  // the change matters
  EXPECT_LT((resolved - direct).norm(), 1e-9 * direct.norm());
  EXPECT_LT((smoother.curvature() - fresh.curvature()).norm(), 1e-12);
}

// solve_after(): α + A⁻¹δb from the changed entries of b equals a smoother built from the changed matching (an edge
// changed twice, a boundary-free mesh's random edges, one change of 0), and leaves the smoother exactly as it was.
TEST(Smoothing, SolveAfterChangesEqualsTheChangedSmoothersSolve) {
  const Propagated s = propagated("fertility_genus4");
  FrameSmoother smoother(s.mesh, s.field, s.stability, s.trusted, {}, 0.5);
  const Eigen::VectorXd alpha = smoother.solve();
  const Eigen::VectorXd theta = smoother.curvature();
  std::vector<MatchingChange> changes;
  std::mt19937 rng(11);
  for (int i = 0; i < 8; ++i)
    changes.push_back({static_cast<int>(rng() % static_cast<unsigned>(s.mesh.num_edges())), i % 2 ? 1 : -2});
  changes.push_back({changes[2].edge, 3});
  changes.push_back({changes[4].edge, 0});
  FrameField changed = s.field;
  for (const MatchingChange& c : changes) changed.matching[c.edge] += c.delta;
  const Eigen::VectorXd after = smoother.solve_after(alpha, changes);
  const Eigen::VectorXd direct = FrameSmoother(s.mesh, changed, s.stability, s.trusted, {}, 0.5).solve();
  EXPECT_GT((after - alpha).norm(), 1e-3);  // the changes matter
  EXPECT_LT((after - direct).norm(), 1e-10 * direct.norm());
  EXPECT_EQ(smoother.matching(), s.field.matching);
  EXPECT_EQ(smoother.curvature(), theta);  // exactly: θ and b are restored, not changed back
  EXPECT_EQ(smoother.solve(), alpha);
  EXPECT_EQ(smoother.solve_after(alpha, std::span<const MatchingChange>{}), alpha);
}

// Alignment targets β (E_A = Σ a_t(α_t - β_t)²) only move b: the re-solve minimizes the new energy, equals a
// smoother that starts from the frames rotated by β with zero targets (up to that rotation), and β = 0 restores
// the thesis solution.
TEST(Smoothing, AlignmentTargets) {
  const Propagated s = propagated("torus_5k");
  const double lambda = 0.5;
  FrameSmoother smoother(s.mesh, s.field, s.stability, s.trusted, {}, lambda);
  const Eigen::VectorXd plain = smoother.solve();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> angle(-0.3, 0.3);
  Eigen::VectorXd beta(s.mesh.num_faces());
  for (int t = 0; t < beta.size(); ++t) beta[t] = angle(rng);
  smoother.set_alignment_targets(beta);
  const Eigen::VectorXd alpha = smoother.solve();
  EXPECT_GT((alpha - plain).norm(), 1e-2);
  const auto E = [&](const Eigen::VectorXd& a) {
    return lambda * smoother.smoothing_energy(a) + (1 - lambda) * smoother.alignment_energy(a);
  };
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::VectorXd d(s.mesh.num_faces());
    for (int t = 0; t < d.size(); ++t) d[t] = normal(rng);
    EXPECT_GT(E(alpha + 1e-3 * d), E(alpha));
  }
  // Rotating the input by β: α' = α - β solves the problem with zero targets (matching unchanged; |β| < π/4
  // keeps every wrapped θ away from ±π here, so θ' = θ - β_s + β_t exactly).
  FrameField turned = s.field;
  for (int t = 0; t < beta.size(); ++t) turned.X[t] *= std::polar(1.0, beta[t]);
  turned.Y = Complex(0, 1) * turned.X;
  const FrameSmoother shifted(s.mesh, turned, s.stability, s.trusted, {}, lambda);
  EXPECT_LT((shifted.solve() - (alpha - beta)).norm(), 1e-8 * alpha.norm());
  smoother.set_alignment_targets(Eigen::VectorXd::Zero(s.mesh.num_faces()));
  EXPECT_LT((smoother.solve() - plain).norm(), 1e-10 * plain.norm());
}

// Fixed faces never rotate; with λ = 1 and no fixed faces one face per component is pinned (A is singular
// otherwise) and the result is a minimizer of E_S alone.
TEST(Smoothing, FixedFacesAndPinning) {
  const Propagated s = propagated("bunny_3k");
  std::vector<char> fixed(static_cast<std::size_t>(s.mesh.num_faces()), 0);
  for (int t = 0; t < s.mesh.num_faces(); t += 13) fixed[static_cast<std::size_t>(t)] = 1;
  const FrameSmoother with_fixed(s.mesh, s.field, s.stability, s.trusted, fixed, 0.8);
  const Eigen::VectorXd alpha = with_fixed.solve();
  for (int t = 0; t < s.mesh.num_faces(); t += 13) EXPECT_EQ(alpha[t], 0.0);
  const FrameField rotated = with_fixed.rotated(alpha);
  for (int t = 0; t < s.mesh.num_faces(); t += 13) EXPECT_EQ(rotated.X[t], s.field.X[t]);

  const FrameSmoother pure(s.mesh, s.field, s.stability, s.trusted, {}, 1.0);
  EXPECT_EQ(pure.num_unknowns(), s.mesh.num_faces() - 1);
  const Eigen::VectorXd a = pure.solve();
  // A common rotation does not change E_S: shifting the pinned solution keeps the energy.
  EXPECT_NEAR(pure.smoothing_energy(a), pure.smoothing_energy((a.array() + 0.3).matrix()), 1e-9);
}

// Factoring A (5.4) before X⁰ is known (compute_frame_field does it during the fill) and setting X⁰ later, also
// a second X⁰ and after alignment targets, gives the smoother built from X⁰ directly, bit for bit.
TEST(Smoothing, FactoringBeforeTheInputMatchesTheDirectConstruction) {
  const Propagated s = propagated("bunny_3k");
  FrameSmoother late(s.mesh, s.stability, s.trusted, {}, 0.5);
  FrameField other = s.field;
  for (Eigen::Index t = 0; t < other.X.size(); ++t) other.X[t] *= std::polar(1.0, 0.1 * std::sin(double(t)));
  late.set_input(make_cross_field(other.X, other.matching));
  late.set_input(s.field);
  const FrameSmoother direct(s.mesh, s.field, s.stability, s.trusted, {}, 0.5);
  const Eigen::VectorXd alpha = direct.solve();
  EXPECT_EQ(late.solve(), alpha);
  EXPECT_GT(alpha.norm(), 0.0);

  Eigen::VectorXd beta(s.mesh.num_faces());
  for (Eigen::Index t = 0; t < beta.size(); ++t) beta[t] = 0.2 * std::cos(double(t));
  FrameSmoother direct_targets(s.mesh, s.field, s.stability, s.trusted, {}, 0.5);
  direct_targets.set_alignment_targets(beta);
  FrameSmoother late_targets(s.mesh, s.stability, s.trusted, {}, 0.5);
  late_targets.set_alignment_targets(beta);
  late_targets.set_input(s.field);
  const Eigen::VectorXd with_targets = direct_targets.solve();
  EXPECT_LT((late_targets.solve() - with_targets).norm(), 1e-12 * with_targets.norm());
  EXPECT_GT((with_targets - alpha).norm(), 1e-3);  // the targets do move the minimizer
}

}  // namespace
}  // namespace quadcover
