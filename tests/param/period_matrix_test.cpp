// The period matrix of the symmetric paths (thesis 6.3.2) and period rounding inside parameterize().
#include "param/period_matrix.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "field/compute_frame_field.h"
#include "param/parameterize.h"
#include "param/seams.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

using testing::load_test_mesh;

// H_d as a dense field for the real variable `var` (Re or Im of the unit jump on one free path).
FramePairs dense_harmonic(const Mesh& mesh, const HarmonicCorrection& hc, const SparseJumpField& s, bool imaginary) {
  FramePairs S = FramePairs::Zero(mesh.num_faces(), 2);
  for (std::size_t k = 0; k < s.support.size(); ++k) {
    if (imaginary)
      S.row(s.support[k]) << -s.Y[k], s.X[k];  // i(X, Y) = (−Y, X)
    else
      S.row(s.support[k]) << s.X[k], s.Y[k];
  }
  return hc.harmonic_part(S);
}

// P_ij = ⟨H_i, Σ_j⟩ with sparse Σ_j equals the Gram matrix ⟨H_i, H_j⟩ of the dense harmonic fields, both for the
// real and the imaginary unit jumps (the latter computed with the quarter turn of Σ, not by P's shortcut).
TEST(PeriodMatrix, EqualsGramMatrixOfHarmonicFields) {
  for (const char* name : {"eight_genus2", "lilium_disk"}) {
    const Mesh mesh = load_test_mesh(name);
    const FrameField field = compute_frame_field(mesh);
    const CoverCut cc = build_cover_cut(mesh, field.matching);
    const HarmonicCorrection hc(mesh, cc, std::vector<char>(static_cast<std::size_t>(mesh.num_components()), 0));
    const PeriodMatrix pm = period_matrix(mesh, cc, hc, 5);  // several blocks
    const int m = static_cast<int>(pm.paths.size());
    ASSERT_GT(m, 2) << name;
    EXPECT_EQ(2 * m, cc.h_sym()) << name;
    EXPECT_LT(pm.asymmetry, 1e-8) << name;
    std::vector<FramePairs> H;
    for (bool imaginary : {false, true})
      for (int j : pm.paths) H.push_back(dense_harmonic(mesh, hc, unit_jump_field(mesh, cc, j), imaginary));
    double scale = pm.P.diagonal().maxCoeff(), worst = 0;
    for (int a = 0; a < 2 * m; ++a)
      for (int b = 0; b < 2 * m; ++b) worst = std::max(worst, std::abs(pm.P(a, b) - frame_inner(mesh, H[a], H[b])));
    EXPECT_LT(worst, 1e-8 * scale) << name;
    // Positive definite on the free paths (the dependent paths are excluded).
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(pm.P).eigenvalues().minCoeff(), 0) << name;
  }
}

// The default blocks: 32 right-hand sides on small meshes, then as many as fit 32 MB of dense #V columns, never
// fewer than 4; the matrix is the same whatever the block size.
TEST(PeriodMatrix, BlocksFitTheirMemoryAndGiveTheSameMatrix) {
  EXPECT_EQ(period_block_columns(0), 32);
  EXPECT_EQ(period_block_columns(60000), 32);
  for (int nv : {70000, 135000, 500000, 10000000}) {
    const int k = period_block_columns(nv);
    EXPECT_GE(k, 4) << nv;
    EXPECT_LE(k, 32) << nv;
    if (k > 4) {
      EXPECT_LE(16.0 * k * nv, 32 << 20) << nv;
    }
    if (k < 32) {
      EXPECT_GT(16.0 * (k + 1) * nv, 32 << 20) << nv;
    }
  }
  EXPECT_EQ(period_block_columns(135000), 15);
  EXPECT_EQ(period_block_columns(10000000), 4);
  const Mesh mesh = load_test_mesh("eight_genus2");
  const FrameField field = compute_frame_field(mesh);
  const CoverCut cc = build_cover_cut(mesh, field.matching);
  const HarmonicCorrection hc(mesh, cc, std::vector<char>(static_cast<std::size_t>(mesh.num_components()), 0));
  const PeriodMatrix by_default = period_matrix(mesh, cc, hc), by_three = period_matrix(mesh, cc, hc, 3);
  ASSERT_GT(by_default.paths.size(), 3u);
  EXPECT_LT((by_default.P - by_three.P).cwiseAbs().maxCoeff(), 1e-12 * by_default.P.cwiseAbs().maxCoeff());
}

// E_H of the final map equals xᵀPx of the rounded periods (unit lattice: no even-branch fix-up after rounding, no
// curve alignment), and search rounding never does worse than direct rounding.
TEST(PeriodMatrix, PredictsHarmonicEnergyOfTheMap) {
  for (const char* name : {"bunny_3k", "3holes_genus3"}) {
    const Mesh mesh = load_test_mesh(name);
    const FrameField field = compute_frame_field(mesh);
    ParamOptions o;
    o.lattice = Lattice::Unit;
    o.alignment.enabled = false;
    for (RoundingStrategy s : {RoundingStrategy::Greedy, RoundingStrategy::Search3}) {
      o.rounding.strategy = s;
      const Parameterization P = parameterize(mesh, field, o);
      ASSERT_GT(P.diagnostics.rounding.variables, 0) << name;
      EXPECT_NEAR(P.energy_harmonic, P.diagnostics.rounding.energy_rounded, 1e-7 * (1 + P.energy_harmonic)) << name;
      EXPECT_LE(P.diagnostics.rounding.energy_rounded, P.diagnostics.rounding.energy_direct * (1 + 1e-12)) << name;
      for (std::size_t j = 0; j < P.rounded_periods.size(); ++j) {
        EXPECT_NEAR(P.rounded_periods[j].real(), std::round(P.rounded_periods[j].real()), 1e-12);
        EXPECT_NEAR(P.rounded_periods[j].imag(), std::round(P.rounded_periods[j].imag()), 1e-12);
      }
    }
    o.rounding.strategy = RoundingStrategy::Direct;
    const Parameterization D = parameterize(mesh, field, o);
    o.rounding.strategy = RoundingStrategy::Search3;
    const Parameterization S = parameterize(mesh, field, o);
    EXPECT_LE(S.energy_harmonic, D.energy_harmonic * (1 + 1e-9)) << name;
    EXPECT_EQ(D.diagnostics.rounding.strategy, "direct");
  }
}

// On the rotated lattice the rounded periods lie in (1+i)Z[i] (a + b even), whatever the strategy.
TEST(PeriodMatrix, RotatedLatticeRounding) {
  const Mesh mesh = load_test_mesh("fertility_genus4");
  const FrameField field = compute_frame_field(mesh);
  ParamOptions o;
  o.rounding.strategy = RoundingStrategy::Search3;
  const Parameterization P = parameterize(mesh, field, o);
  ASSERT_GT(P.diagnostics.rounding.variables, 0);
  EXPECT_LE(P.diagnostics.rounding.energy_rounded, P.diagnostics.rounding.energy_direct * (1 + 1e-12));
  for (const Complex c : P.rounded_periods) {
    const long a = std::lround(c.real()), b = std::lround(c.imag());
    EXPECT_NEAR(c.real(), a, 1e-12);
    EXPECT_NEAR(c.imag(), b, 1e-12);
    EXPECT_EQ(((a + b) % 2 + 2) % 2, 0) << c;
  }
}

// A sink that asks to stop once the pipeline has reported `after` stages.
class StopAfter final : public ProgressSink {
 public:
  explicit StopAfter(int after) : after_(after) {}
  void report(std::string_view, double, std::string_view) override { ++reports_; }
  bool cancelled() const override { return reports_ >= after_; }

 private:
  int after_, reports_ = 0;
};

// Cancellation during rounding keeps a valid seamless map: the direct periods (stopped before the period matrix) or
// the search's best so far, never worse than direct rounding.
TEST(PeriodMatrix, CancellationKeepsAValidMap) {
  const Mesh mesh = load_test_mesh("bunny_3k");
  const FrameField field = compute_frame_field(mesh);
  ParamOptions o;
  o.lattice = Lattice::Unit;
  o.rounding.strategy = RoundingStrategy::Search3;
  const Parameterization full = parameterize(mesh, field, o);
  EXPECT_FALSE(full.diagnostics.rounding.stopped_early);
  o.rounding.strategy = RoundingStrategy::Direct;
  const Parameterization direct = parameterize(mesh, field, o);
  o.rounding.strategy = RoundingStrategy::Search3;
  for (int after : {1, 4}) {  // before the period matrix (after cut, ..., harmonic_factor)
    StopAfter stop(after);
    const Parameterization P = parameterize(mesh, field, o, stop);
    EXPECT_TRUE(P.diagnostics.rounding.stopped_early) << after;
    EXPECT_TRUE(measure_seams(mesh, P.uv, 1e-9).seamless) << after;
    EXPECT_LE(P.energy_harmonic, direct.energy_harmonic * (1 + 1e-9)) << after;
    EXPECT_GE(P.energy_harmonic, full.energy_harmonic * (1 - 1e-9)) << after;
  }
}

// The search honours RoundingOptions::stop between passes and returns a vector no worse than its start.
TEST(PeriodRounding, StopReturnsBestSoFar) {
  const int n = 30;
  Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, n);
  const Eigen::MatrixXd P = B.transpose() * B + 0.1 * Eigen::MatrixXd::Identity(n, n);
  const Eigen::VectorXd b = 3 * Eigen::VectorXd::Random(n);
  RoundingOptions o;
  o.strategy = RoundingStrategy::Search3;
  const RoundingResult full = round_periods(P, b, o);
  int calls = 0;
  o.stop = [&calls] { return ++calls > 2; };
  const RoundingResult part = round_periods(P, b, o);
  EXPECT_TRUE(part.stopped_early);
  EXPECT_FALSE(full.stopped_early);
  o.strategy = RoundingStrategy::Direct;
  const double direct = round_periods(P, b, o).energy;
  EXPECT_LE(part.energy, direct);
  EXPECT_GE(part.energy, full.energy * (1 - 1e-12));
  EXPECT_LT(part.moves, full.moves);
  // The candidate budget stops the search the same way.
  o.strategy = RoundingStrategy::Search3;
  o.stop = nullptr;
  o.max_candidates = full.candidates / 4;
  const RoundingResult budget = round_periods(P, b, o);
  EXPECT_TRUE(budget.stopped_early);
  EXPECT_LE(budget.energy, direct);
  EXPECT_GE(budget.energy, full.energy * (1 - 1e-12));
  EXPECT_LE(budget.candidates, full.candidates);
}

}  // namespace
}  // namespace quadcover
