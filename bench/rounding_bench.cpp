// Rounding comparison of thesis 6.3.3 (100 instances, mean E_H relative to direct rounding; thesis: MIQ greedy
// 61.0%, r=1 63.8%, r=3 54.8%), here on synthetic period-like instances: P = RᵀR with R upper triangular,
// diagonal 1 + 0.3|N(0,1)| and off-diagonal 1.5·N(0,1)/√n (diagonal of P ≈ 2-3 as in 6.4), periods uniform in
// [-3, 3] (fractional parts uniform, as assumed in 6.4). Prints the table, then times each strategy.
//   bench_rounding [--benchmark_flags...] [n=40] [instances=100]
#include <benchmark/benchmark.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "param/period_rounding.h"

namespace {

using namespace quadcover;

struct Instance {
  Eigen::MatrixXd P;
  Eigen::VectorXd b;
};

Instance make_instance(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(-3, 3);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    R(i, i) = 1.0 + 0.3 * std::abs(g(rng));
    for (int j = i + 1; j < n; ++j) R(i, j) = 1.5 * g(rng) / std::sqrt(n);
  }
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = u(rng);
  return {R.transpose() * R, b};
}

std::vector<Instance> g_instances;

void BM_Strategy(benchmark::State& state, RoundingStrategy s) {
  RoundingOptions o;
  o.strategy = s;
  long long candidates = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& in = g_instances[i++ % g_instances.size()];
    candidates += round_periods(in.P, in.b, o).candidates;
  }
  state.counters["candidates_per_s"] = benchmark::Counter(static_cast<double>(candidates), benchmark::Counter::kIsRate);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  const int n = argc > 1 ? std::stoi(argv[1]) : 40;
  const int count = argc > 2 ? std::stoi(argv[2]) : 100;
  for (int k = 0; k < count; ++k) g_instances.push_back(make_instance(n, 1000 + k));
  const RoundingStrategy all[] = {RoundingStrategy::Direct,  RoundingStrategy::Greedy,  RoundingStrategy::Search1,
                                  RoundingStrategy::Search2, RoundingStrategy::Search3, RoundingStrategy::Exact};
  double sum[6] = {0};
  int proven = 0;
  for (const auto& in : g_instances) {
    double direct = 0;
    for (int s = 0; s < 6; ++s) {
      RoundingOptions o;
      o.strategy = all[s];
      const RoundingResult r = round_periods(in.P, in.b, o);
      if (s == 0) direct = r.energy;
      sum[s] += r.energy / direct;
      if (s == 5) proven += r.proven_optimal;
    }
  }
  std::printf("| n | instances | direct | greedy (MIQ) | r=1 | r=2 | r=3 | exact (proven %d/%d) |\n", proven, count);
  std::printf("| %d | %d |", n, count);
  for (double v : sum) std::printf(" %.1f%% |", 100.0 * v / count);
  std::printf("\n");
  for (auto s : all)
    benchmark::RegisterBenchmark(("Round/" + to_string(s)).c_str(), BM_Strategy, s)->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
