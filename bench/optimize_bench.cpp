// Table 6.1 (thesis 6.2.1): average time of one E_D re-evaluation after a matching change, from scratch and via
// Cholesky updates, split by stage; plus the plain CXSparse route (two cs_ci_updown + a full forward solve) and the
// reach-limited evaluation (fixed field, sparse right-hand side: only the etree paths of the changed rows).
// Meshes: the non-flag arguments, else tests/data/bunny_3k.obj and bunny_20k_holes.obj plus the ':'-separated
// list in $QUADCOVER_BENCH_MESHES (e.g. /work/shared/meshes/armadillo_86k.obj:/work/shared/meshes/igea_270k.obj).
//   bench_optimize [--benchmark_flags...] [mesh...]
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cover/complex_stiffness.h"
#include "field/compute_frame_field.h"
#include "io/read_mesh.h"
#include "optimize/curl_energy.h"
#include "param/period_rounding.h"

namespace {

using namespace quadcover;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct BenchMesh {
  std::string name;
  Mesh mesh;
  FrameFieldResult field;
  std::unique_ptr<FrameSmoother> smoother;
  std::unique_ptr<CurlEnergy> energy;
  std::vector<int> edges;  // interior edges
};
std::vector<std::unique_ptr<BenchMesh>> g_meshes;

std::unique_ptr<BenchMesh> load(const std::string& path) {
  auto b = std::make_unique<BenchMesh>();
  b->name = std::filesystem::path(path).stem().string();
  b->mesh = build_mesh(read_mesh(path)).mesh;
  b->field = compute_frame_field_detailed(b->mesh);
  b->smoother = std::make_unique<FrameSmoother>(b->mesh, b->field.field, b->field.stability, b->field.trusted,
                                                b->field.constrained, FieldOptions{}.lambda);
  b->energy = std::make_unique<CurlEnergy>(b->mesh, *b->smoother);
  for (int e = 0; e < b->mesh.num_edges(); ++e)
    if (!b->mesh.is_boundary_edge(e)) b->edges.push_back(e);
  return b;
}

void set_ms(benchmark::State& state, const char* key, double seconds, long n) {
  state.counters[key] = benchmark::Counter(1e3 * seconds / std::max(1L, n));
}

// From scratch: min E(α), curl* from α, assemble + decompose 𝔏̄* = LᴴL, solve Lx = b.
void BM_FromScratch(benchmark::State& state, BenchMesh* b) {
  double t_smooth = 0, t_curl = 0, t_decompose = 0, t_solve = 0, t_other = 0;
  long n = 0;
  for (auto _ : state) {
    auto t = Clock::now();
    const Eigen::VectorXd alpha = b->smoother->solve();
    t_smooth += since(t), t = Clock::now();
    const FrameField f = b->smoother->rotated(alpha);
    const Eigen::VectorXcd rhs = -complex_curl_star(b->mesh, f);
    t_curl += since(t), t = Clock::now();
    const auto A = complex_nonconforming_stiffness(b->mesh, f.matching);
    t_other += since(t), t = Clock::now();
    UpdatableCholesky F(A);
    t_decompose += since(t), t = Clock::now();
    F.set_rhs(rhs);
    t_solve += since(t);
    benchmark::DoNotOptimize(F.rhs_energy());
    ++n;
  }
  set_ms(state, "minE_ms", t_smooth, n), set_ms(state, "curl_ms", t_curl, n);
  set_ms(state, "decompose_ms", t_decompose, n), set_ms(state, "solve_ms", t_solve, n);
  set_ms(state, "other_ms", t_other, n);
  state.counters["faces"] = b->mesh.num_faces();
}

// Via updates: CurlEnergy::evaluate of a random single-edge change (not committed), stages as in Table 6.1.
void BM_ViaUpdates(benchmark::State& state, BenchMesh* b) {
  std::mt19937 rng(1);
  std::uniform_int_distribution<std::size_t> pick(0, b->edges.size() - 1);
  b->energy->reset_timings();
  for (auto _ : state) {
    const MatchingChange c{b->edges[pick(rng)], rng() % 2 ? 1 : -1};
    benchmark::DoNotOptimize(b->energy->evaluate(std::span(&c, 1)));
  }
  const auto& t = b->energy->timings();
  set_ms(state, "minE_ms", t.smoothing, t.evaluations), set_ms(state, "curl_ms", t.curl, t.evaluations);
  set_ms(state, "update_ms", t.update, t.evaluations), set_ms(state, "solve_ms", t.solve, t.evaluations);
  set_ms(state, "other_ms", t.other, t.evaluations);
  state.counters["factor_nnz"] = static_cast<double>(b->energy->factor().factor_nonzeros());
}

// Plain CXSparse: two cs_ci_updown (Deng order) + one full forward solve, then the inverse change (not timed).
void BM_PlainCxsparse(benchmark::State& state, BenchMesh* b) {
  UpdatableCholesky F(complex_nonconforming_stiffness(b->mesh, b->energy->matching()) +
                      [&] {
                        Eigen::SparseMatrix<Complex> I(b->mesh.num_edges(), b->mesh.num_edges());
                        I.setIdentity();
                        return 1e-10 * I;
                      }());
  F.set_rhs(-complex_curl_star(b->mesh, b->energy->field()));
  std::mt19937 rng(2);
  std::uniform_int_distribution<std::size_t> pick(0, b->edges.size() - 1);
  for (auto _ : state) {
    const int e = b->edges[pick(rng)];
    StarChange c = b->energy->stiffness_change(e, 1);
    F.apply_star_change_cxsparse(c);
    state.PauseTiming();
    for (auto& d : c.d) d.value = -d.value;
    F.apply_star_change_cxsparse(c);
    state.ResumeTiming();
  }
}

// Reach-limited (beyond the thesis; field held fixed): star change + curl* change at e only, forward solve
// restricted to the etree paths of the changed rows.
void BM_ReachLimited(benchmark::State& state, BenchMesh* b) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<std::size_t> pick(0, b->edges.size() - 1);
  FactorTrial trial(b->energy->factor().size());
  long reach = 0, n = 0;
  for (auto _ : state) {
    const int e = b->edges[pick(rng)];
    trial.reset();
    trial.add_star_change(b->energy->factor(), b->energy->stiffness_change(e, 1));
    const SparseEntry db{e, Complex(0.1, 0.1)};
    trial.add_rhs_change(b->energy->factor(), std::span(&db, 1));
    benchmark::DoNotOptimize(trial.evaluate(b->energy->factor()));
    reach += trial.reach(), ++n;
  }
  state.counters["reach_columns"] = static_cast<double>(reach) / std::max(1L, n);
}

// Rounding on synthetic period-like instances (correlated SPD P, periods uniform in [-3,3]): candidates per second.
void BM_RoundingSearch3(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(-3, 3);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    R(i, i) = 1.0 + 0.3 * std::abs(g(rng));
    for (int j = i + 1; j < n; ++j) R(i, j) = 1.5 * g(rng) / std::sqrt(n);
  }
  const Eigen::MatrixXd P = R.transpose() * R;
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = u(rng);
  long long candidates = 0;
  for (auto _ : state) candidates += round_periods(P, b).candidates;
  state.counters["candidates_per_s"] = benchmark::Counter(static_cast<double>(candidates), benchmark::Counter::kIsRate);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i) paths.emplace_back(argv[i]);
  if (paths.empty()) {
    const std::string data = std::string(QUADCOVER_SOURCE_DIR) + "/tests/data/";
    paths = {data + "bunny_3k.obj", data + "bunny_20k_holes.obj"};
    if (const char* extra = std::getenv("QUADCOVER_BENCH_MESHES")) {
      std::stringstream ss(extra);
      for (std::string p; std::getline(ss, p, ':');)
        if (!p.empty()) paths.push_back(p);
    }
  }
  for (const auto& p : paths) {
    g_meshes.push_back(load(p));
    BenchMesh* b = g_meshes.back().get();
    benchmark::RegisterBenchmark(("FromScratch/" + b->name).c_str(), BM_FromScratch, b)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("ViaUpdates/" + b->name).c_str(), BM_ViaUpdates, b)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("PlainCXSparse/" + b->name).c_str(), BM_PlainCxsparse, b)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("ReachLimited/" + b->name).c_str(), BM_ReachLimited, b)
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RegisterBenchmark("RoundingSearch3", BM_RoundingSearch3)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
