// Rounding of periods (thesis 6.3): the exact closest vector equals brute-force enumeration, every heuristic is
// bounded by it and by direct rounding, and the search strategies end in r-local minima (checked exhaustively).
#include <gtest/gtest.h>

#include <random>

#include "common/errors.h"
#include "param/period_rounding.h"

namespace quadcover {
namespace {

// A correlated SPD matrix like a period matrix (diagonal ~2-3, strong couplings) and periods spread over [-3, 3].
std::pair<Eigen::MatrixXd, Eigen::VectorXd> instance(int n, unsigned seed, double coupling = 1.5) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(-3, 3);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    R(i, i) = 1.0 + 0.3 * std::abs(g(rng));
    for (int j = i + 1; j < n; ++j) R(i, j) = coupling * g(rng) / std::sqrt(n);
  }
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = u(rng);
  return {R.transpose() * R, b};
}

double energy_of(const Eigen::MatrixXd& P, const Eigen::VectorXd& b, RoundingStrategy s) {
  RoundingOptions o;
  o.strategy = s;
  return round_periods(P, b, o).energy;
}

// Minimum of E_H over c ∈ [b] + {-2..2}ⁿ.
double brute_force(const Eigen::MatrixXd& P, const Eigen::VectorXd& b) {
  const int n = static_cast<int>(b.size());
  Eigen::VectorXi base(n), c(n);
  for (int i = 0; i < n; ++i) base[i] = static_cast<int>(std::lround(b[i]));
  double best = 1e300;
  long total = 1;
  for (int i = 0; i < n; ++i) total *= 5;
  for (long code = 0; code < total; ++code) {
    long r = code;
    for (int i = 0; i < n; ++i, r /= 5) c[i] = base[i] + static_cast<int>(r % 5) - 2;
    best = std::min(best, rounding_energy(P, b, c));
  }
  return best;
}

TEST(Rounding, ExactEqualsBruteForceOnSmallInstances) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    auto [P, b] = instance(5, seed);
    RoundingOptions o;
    o.strategy = RoundingStrategy::Exact;
    const RoundingResult r = round_periods(P, b, o);
    EXPECT_TRUE(r.proven_optimal);
    EXPECT_NEAR(r.energy, brute_force(P, b), 1e-9) << "seed " << seed;
    EXPECT_NEAR(r.energy, rounding_energy(P, b, r.c), 1e-12);
  }
}

TEST(Rounding, EveryStrategyLiesBetweenExactAndDirect) {
  double sum_direct = 0, sum_greedy = 0, sum_s3 = 0, sum_exact = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    auto [P, b] = instance(24, 100 + seed);
    const double direct = energy_of(P, b, RoundingStrategy::Direct);
    const double exact = energy_of(P, b, RoundingStrategy::Exact);
    for (auto s : {RoundingStrategy::Search1, RoundingStrategy::Search2, RoundingStrategy::Search3}) {
      const double e = energy_of(P, b, s);
      EXPECT_LE(e, direct + 1e-12);  // the searches start at [b] and only accept decreases
      EXPECT_GE(e, exact - 1e-9);
    }
    const double greedy = energy_of(P, b, RoundingStrategy::Greedy);
    EXPECT_GE(greedy, exact - 1e-9);
    EXPECT_LE(energy_of(P, b, RoundingStrategy::Search3), greedy + 1e-12);  // also started from the greedy result
    sum_direct += direct, sum_greedy += greedy, sum_s3 += energy_of(P, b, RoundingStrategy::Search3);
    sum_exact += exact;
  }
  // On correlated instances optimized rounding is clearly better than direct rounding (6.3.3).
  EXPECT_LT(sum_greedy, 0.9 * sum_direct);
  EXPECT_LT(sum_s3, 0.9 * sum_direct);
  EXPECT_LT(sum_exact, sum_s3 + 1e-9);
}

// After Search_r no change of at most r entries by ±1 lowers E_H (exhaustive check of the neighbourhood).
TEST(Rounding, SearchEndsInLocalMinimumOfItsNeighbourhood) {
  auto [P, b] = instance(11, 77);
  for (int r = 1; r <= 3; ++r) {
    RoundingOptions o;
    o.strategy = r == 1 ? RoundingStrategy::Search1 : r == 2 ? RoundingStrategy::Search2 : RoundingStrategy::Search3;
    const RoundingResult res = round_periods(P, b, o);
    EXPECT_GT(res.candidates, 0);
    const int n = static_cast<int>(b.size());
    // Enumerate σ ∈ {-1,0,1}ⁿ with at most r nonzeros.
    std::vector<int> sigma(n, 0);
    long total = 1;
    for (int i = 0; i < n; ++i) total *= 3;
    for (long code = 1; code < total; ++code) {
      long q = code;
      int nz = 0;
      for (int i = 0; i < n; ++i, q /= 3) sigma[i] = static_cast<int>(q % 3) - 1, nz += sigma[i] != 0;
      if (nz > r) continue;
      Eigen::VectorXi c = res.c;
      for (int i = 0; i < n; ++i) c[i] += sigma[i];
      ASSERT_GE(rounding_energy(P, b, c), res.energy - 1e-9) << "r = " << r;
    }
  }
}

// With a diagonal period matrix the variables decouple: every strategy must return direct rounding.
TEST(Rounding, DecoupledPeriodsRoundDirectly) {
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(6, 6);
  P.diagonal() << 2, 3, 2.5, 1, 4, 2.2;
  Eigen::VectorXd b(6);
  b << 0.4, -1.7, 2.49, 3.51, -0.2, 7.9;
  Eigen::VectorXi direct(6);
  direct << 0, -2, 2, 4, 0, 8;
  for (auto s : {RoundingStrategy::Direct, RoundingStrategy::Greedy, RoundingStrategy::Search1,
                 RoundingStrategy::Search3, RoundingStrategy::Exact}) {
    RoundingOptions o;
    o.strategy = s;
    EXPECT_EQ(round_periods(P, b, o).c, direct) << to_string(s);
  }
}

TEST(Rounding, ExactFallsBackToSearchAboveTheDimensionLimit) {
  auto [P, b] = instance(30, 5);
  RoundingOptions o;
  o.strategy = RoundingStrategy::Exact;
  o.exact_max_dimension = 20;
  const RoundingResult r = round_periods(P, b, o);
  EXPECT_EQ(r.used, RoundingStrategy::Search3);
  EXPECT_FALSE(r.proven_optimal);
  EXPECT_NEAR(r.energy, energy_of(P, b, RoundingStrategy::Search3), 1e-12);
}

TEST(Rounding, StrategyNamesRoundTripAndBadNamesThrow) {
  for (auto s : {RoundingStrategy::Direct, RoundingStrategy::Greedy, RoundingStrategy::Search1,
                 RoundingStrategy::Search2, RoundingStrategy::Search3, RoundingStrategy::Exact})
    EXPECT_EQ(parse_rounding_strategy(to_string(s)), s);
  EXPECT_THROW(parse_rounding_strategy("nearest"), InputError);
  EXPECT_THROW(round_periods(Eigen::MatrixXd::Identity(3, 3), Eigen::VectorXd::Zero(2)), InputError);
}

}  // namespace
}  // namespace quadcover
