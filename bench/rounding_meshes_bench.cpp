// Rounding comparison of thesis 6.3.3 on real period matrices (6.3.2): every shipped test mesh at several densities
// (target quad counts #F/48 … #F/2, 8 densities: 104 instances), curvature-free smooth field (field stage defaults), unit lattice Z[i], no
// curve alignment, so that E_H of the map equals xᵀPx of the rounded periods. Per instance, E_H of each strategy
// relative to direct rounding; the table prints means over all instances (thesis, 100 instances: MIQ greedy 61.0%,
// r=1 63.8%, r=3 54.8%) and the exact optimum where the dimension allows (2m ≤ 48).
//   bench_rounding_meshes [--table]   (--table: only the Markdown table; otherwise also Google Benchmark timings)
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "field/compute_frame_field.h"
#include "io/read_mesh.h"
#include "param/parameterize.h"

namespace {

using namespace quadcover;

const char* const kMeshes[] = {"bunny_3k",    "torus_5k",          "eight_genus2",       "3holes_genus3",
                               "fertility_genus4", "couplingdown_genus9", "lilium_disk", "camelhead_boundary",
                               "mech_holes_shark", "bunny_20k_holes",  "spot",        "cow", "fandisk"};
const int kDivisors[] = {48, 32, 24, 16, 12, 8, 4, 2};
const RoundingStrategy kStrategies[] = {RoundingStrategy::Greedy, RoundingStrategy::Search1,
                                        RoundingStrategy::Search2, RoundingStrategy::Search3,
                                        RoundingStrategy::Exact};

Mesh load(const char* name) {
  return build_mesh(read_mesh(std::string(QUADCOVER_SOURCE_DIR) + "/tests/data/" + name + ".obj")).mesh;
}

void print_table() {
  const int ns = static_cast<int>(std::size(kStrategies));
  std::vector<double> sum(ns, 0), exact_sum(ns, 0);
  std::vector<int> wins(ns, 0);
  int instances = 0, exact_instances = 0, proven = 0;
  double vars = 0, seconds = 0;
  for (const char* name : kMeshes) {
    const Mesh mesh = load(name);
    const FrameField field = compute_frame_field(mesh);
    for (int div : kDivisors) {
      ParamOptions o;
      o.lattice = Lattice::Unit;
      o.alignment.enabled = false;
      o.density.target_quads = std::max(16, mesh.num_faces() / div);
      std::vector<double> e(ns);
      double direct = 0;
      bool exact_done = false;
      for (int k = 0; k < ns; ++k) {
        o.rounding.strategy = kStrategies[k];
        const Parameterization P = parameterize(mesh, field, o);
        if (P.diagnostics.rounding.variables == 0) break;
        direct = P.diagnostics.rounding.energy_direct;
        e[k] = P.diagnostics.rounding.energy_rounded;
        if (k == 0) vars += P.diagnostics.rounding.variables;
        for (const auto& [stage, sec] : P.diagnostics.stage_seconds)
          if (stage == "period_rounding") seconds += sec;
        if (kStrategies[k] == RoundingStrategy::Exact && P.diagnostics.rounding.strategy == "exact") {
          exact_done = true;
          proven += P.diagnostics.rounding.proven_optimal;
        }
      }
      if (!(direct > 0)) continue;
      ++instances;
      for (int k = 0; k < ns; ++k) sum[k] += e[k] / direct;
      if (exact_done) {
        ++exact_instances;
        for (int k = 0; k < ns; ++k) {
          exact_sum[k] += e[k] / direct;
          wins[k] += e[k] <= e[ns - 1] * (1 + 1e-9);
        }
      }
    }
  }
  std::printf("%d instances (%zu meshes x %zu densities), mean %.0f real variables, mean period matrix + rounding "
              "time %.3f s\n\n",
              instances, std::size(kMeshes), std::size(kDivisors), vars / instances, seconds / (instances * ns));
  std::printf("| strategy | mean E_H / direct (all %d) | mean E_H / direct (%d with exact) | optimal on those |\n",
              instances, exact_instances);
  std::printf("|---|---|---|---|\n");
  const char* names[] = {"greedy (MIQ)", "search r=1", "search r=2", "search r=3", "exact (LLL + enumeration)"};
  for (int k = 0; k < ns; ++k)
    std::printf("| %s | %.1f%% | %s | %s |\n", names[k], 100 * sum[k] / instances,
                exact_instances ? (std::to_string(100 * exact_sum[k] / exact_instances).substr(0, 4) + "%").c_str()
                                : "–",
                exact_instances ? (std::to_string(wins[k]) + " / " + std::to_string(exact_instances)).c_str() : "–");
  std::printf("\nexact runs proven optimal: %d\n", proven);
}

void BM_ParamRounding(benchmark::State& state, RoundingStrategy s) {
  static const Mesh mesh = load("bunny_20k_holes");
  static const FrameField field = compute_frame_field(mesh);
  ParamOptions o;
  o.alignment.enabled = false;
  o.rounding.strategy = s;
  for (auto _ : state) benchmark::DoNotOptimize(parameterize(mesh, field, o).energy_harmonic);
}
BENCHMARK_CAPTURE(BM_ParamRounding, direct, RoundingStrategy::Direct)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ParamRounding, greedy, RoundingStrategy::Greedy)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ParamRounding, search3, RoundingStrategy::Search3)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  bool table_only = false;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--table") == 0) table_only = true;
  print_table();
  if (table_only) return 0;
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
