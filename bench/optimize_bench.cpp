// Table 6.1 (thesis 6.2.1): average time of one E_D re-evaluation after a matching change, from scratch and via
// Cholesky updates, split by stage; plus the plain CXSparse route (two cs_ci_updown + a full forward solve) and the
// reach-limited evaluation (fixed field, sparse right-hand side: only the etree paths of the changed rows).
// Local estimate (CurlEnergy::estimate: patch re-smoothing, sparse curl* change, reach-limited solve, first-order
// far field), serially and as 2-thread batches. With QUADCOVER_BENCH_PIPELINE=1 also the whole optimized
// pipeline per mesh (field, optimize_field full, parameterize), once; with QUADCOVER_BENCH_SWEEP=1 the Figure 6.5
// sweep (balancing_sweep with creation) is printed for the first mesh.
// Meshes: the non-flag arguments, else tests/data/bunny_3k.obj and bunny_20k_holes.obj plus the ':'-separated
// list in $QUADCOVER_BENCH_MESHES (e.g. /work/shared/meshes/armadillo_86k.obj:/work/shared/meshes/igea_270k.obj).
//   bench_optimize [--benchmark_flags...] [mesh...]
#include <benchmark/benchmark.h>
#include <cs.h>

#include <chrono>
#include <cmath>
#include <cstdio>
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
#include "optimize/balancing_sweep.h"
#include "optimize/curl_energy.h"
#include "optimize/curl_estimator.h"
#include "optimize/local_smoothing.h"
#include "optimize/optimize_field.h"
#include "param/period_rounding.h"
#include "pipeline/parameterize_mesh.h"

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
  UpdatableCholesky F(complex_nonconforming_stiffness(b->mesh, b->energy->matching()) + [&] {
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

// Local estimate of a random single-edge change (serial workspace; stages: local CG = minE, curl* change, star
// updates, reach-limited forward solve).
void BM_LocalEstimate(benchmark::State& state, BenchMesh* b) {
  std::mt19937 rng(4);
  std::uniform_int_distribution<std::size_t> pick(0, b->edges.size() - 1);
  CurlEstimator estimator(*b->energy);
  estimator.prepare();
  EstimateWorkspace ws;
  for (auto _ : state) {
    const MatchingChange c{b->edges[pick(rng)], rng() % 2 ? 1 : -1};
    benchmark::DoNotOptimize(estimator.estimate(std::span(&c, 1), ws));
  }
  const auto& t = ws.timings;
  set_ms(state, "minE_ms", t.smoothing, t.evaluations), set_ms(state, "curl_ms", t.curl, t.evaluations);
  set_ms(state, "update_ms", t.update, t.evaluations), set_ms(state, "solve_ms", t.solve, t.evaluations);
  state.counters["patch_faces"] = static_cast<double>(ws.patch_faces) / std::max(1L, t.evaluations);
  state.counters["reach_columns"] = static_cast<double>(ws.reach_columns) / std::max(1L, t.evaluations);
}

// 64 candidates per batch on 2 threads (CurlEstimator::estimate_batch); time per candidate = time / 64.
void BM_EstimateBatch2(benchmark::State& state, BenchMesh* b) {
  std::mt19937 rng(6);
  std::uniform_int_distribution<std::size_t> pick(0, b->edges.size() - 1);
  std::vector<std::vector<MatchingChange>> cands(64);
  std::vector<double> out(cands.size());
  CurlEstimator estimator(*b->energy);
  double seconds = 0;
  long n = 0;
  for (auto _ : state) {
    state.PauseTiming();
    for (auto& c : cands) c.assign(1, MatchingChange{b->edges[pick(rng)], rng() % 2 ? 1 : -1});
    state.ResumeTiming();
    const auto t = Clock::now();
    estimator.estimate_batch(cands, out, 2);
    seconds += since(t), n += static_cast<long>(cands.size());
  }
  set_ms(state, "per_candidate_ms", seconds, n);
}

// The whole optimized pipeline (wall clock): the library's parameterization job (pipeline/parameterize_mesh.h) with
// --optimize full: field (Chapter 5), Algorithm 6.1 + balancing, parameterize (Chapter 4 + rounding 6.3), and the
// job's other stages at their defaults.
void BM_OptimizedPipeline(benchmark::State& state, std::string path) {
  for (auto _ : state) {
    const Mesh mesh = build_mesh(read_mesh(path)).mesh;
    PipelineOptions po;
    po.optimize = OptimizeMode::Full;
    // Override for calibration: QUADCOVER_BENCH_BUDGET (evaluations, 0 = unlimited).
    if (const char* v = std::getenv("QUADCOVER_BENCH_BUDGET")) po.max_evaluations = std::atol(v);
    const ParamJob job = parameterize_mesh(mesh, po);
    auto stage = [&](const std::string& name) {  // the stage and its sub-stages (name_*)
      double t = 0;
      for (const auto& [s, seconds] : job.seconds)
        if (s == name || s.rfind(name + "_", 0) == 0) t += seconds;
      return t;
    };
    double total = 0;
    for (const auto& [s, seconds] : job.seconds) total += seconds;
    const nlohmann::json& r = job.optimize;
    state.counters["field_s"] = stage("field"), state.counters["optimize_s"] = stage("optimize");
    state.counters["param_s"] = stage("param");
    state.counters["total_s"] = total;
    state.counters["evaluations"] = r.value("evaluations", 0.0);
    state.counters["exact_evals"] = r.value("exact_evaluations", 0.0);
    state.counters["bp_before"] = r.value("branch_points_before", 0.0);
    state.counters["bp_after"] = r.value("branch_points_after", 0.0);
    state.counters["E_D_before"] = r.value("E_D_before", 0.0);
    state.counters["E_D_after"] = r.value("E_D_after", 0.0);
    state.counters["E_H"] = job.map.energy_harmonic;
    state.counters["stopped_early"] = r.value("stopped_early", false);
    state.counters["faces"] = mesh.num_faces();
    state.counters["accepted"] = r.value("accepted", 0.0);
    state.counters["budget"] = r.value("max_evaluations", 0.0);
    const nlohmann::json& x = r["seconds"]["exact"];
    const nlohmann::json& e = r["seconds"]["estimates"];
    const auto sec = [](const nlohmann::json& j, const char* k) { return j.value(k, 0.0); };
    state.counters["exact_s"] = sec(x, "smoothing") + sec(x, "curl") + sec(x, "update") + sec(x, "solve");
    state.counters["exact_smooth_s"] = sec(x, "smoothing"), state.counters["exact_solve_s"] = sec(x, "solve");
    state.counters["commit_s"] = sec(x, "commit"), state.counters["prepare_s"] = sec(x, "prepare_estimates");
    state.counters["backsolve_s"] = sec(x, "back_solve");
    state.counters["estimates_sum_s"] = sec(e, "smoothing") + sec(e, "curl") + sec(e, "update") + sec(e, "solve");
  }
}

// How far the re-smoothing Δα = A⁻¹Δb of one matching change reaches (5.4): relative error of the patch solution
// (Dirichlet 0 outside `rings` face rings) against the full solve, per ring count, mean and max over 20 edges.
void print_decay(BenchMesh& b) {
  const SmoothingSystem A(b.mesh, *b.smoother);
  std::mt19937 rng(3);
  LocalSmoothingWork w;
  std::printf("%s: rings, patch faces, mean / max relative error of Δα_P\n", b.name.c_str());
  for (int rings : {6, 12, 24, 48, 96}) {
    double mean = 0, worst = 0;
    long patch = 0;
    for (int i = 0; i < 20; ++i) {
      const int e = b.edges[std::uniform_int_distribution<std::size_t>(0, b.edges.size() - 1)(rng)];
      double theta = b.smoother->curvature()[e];
      FaceEntry fe[2];
      const int n = A.rhs_change(e, theta > 0 ? -1 : 1, theta, fe);
      Eigen::VectorXd db = Eigen::VectorXd::Zero(b.mesh.num_faces());
      for (int k = 0; k < n; ++k) db[fe[k].face] += fe[k].value;
      const Eigen::VectorXd exact = A.solve(db);
      A.solve_local(std::span<const FaceEntry>(fe, static_cast<std::size_t>(n)), rings, 1e-12, w);
      Eigen::VectorXd x = Eigen::VectorXd::Zero(b.mesh.num_faces());
      for (std::size_t j = 0; j < w.faces.size(); ++j) x[w.faces[j]] = w.x[j];
      const double err = (x - exact).norm() / std::max(1e-300, exact.norm());
      mean += err / 20, worst = std::max(worst, err);
      patch += static_cast<long>(w.faces.size());
    }
    std::printf("  %3d %7ld %.2e %.2e\n", rings, patch / 20, mean, worst);
  }
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

// The set-up factorization of 𝔏̄* (Algorithm 6.1 before its first evaluation): CXSparse's AMD + up-looking
// cs_ci_chol (the previous UpdatableCholesky), and UpdatableCholesky as it is (the same AMD, CHOLMOD supernodal
// numbers on it); nnz(L) as a counter.
// 𝔏̄* of the mesh's field + ε·I as CurlEnergy shifts it (ε = 1e-10 × mean diagonal).
Eigen::SparseMatrix<Complex> shifted_stiffness(const BenchMesh& b) {
  const Eigen::SparseMatrix<Complex> A = complex_nonconforming_stiffness(b.mesh, b.field.field.matching);
  const double eps = 1e-10 * A.diagonal().cwiseAbs().mean();
  Eigen::SparseMatrix<Complex> out = A + Eigen::SparseMatrix<Complex>(
                                             Eigen::VectorXcd::Constant(A.rows(), Complex(eps, 0)).asDiagonal());
  out.makeCompressed();
  return out;
}
void BM_FactorCxsparse(benchmark::State& state, BenchMesh* b) {
  Eigen::SparseMatrix<Complex> A = shifted_stiffness(*b);
  cs_ci view{static_cast<int>(A.nonZeros()), static_cast<int>(A.rows()), static_cast<int>(A.cols()),
             A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(), -1};
  long nnz = 0;
  for (auto _ : state) {
    cs_cis* S = cs_ci_schol(1, &view);
    cs_cin* N = cs_ci_chol(&view, S);
    nnz = N ? N->L->p[A.rows()] : -1;
    double flops = 0;  // Σ_j c_j² over the column counts of L
    for (int j = 0; j < A.rows(); ++j) flops += std::pow(static_cast<double>(S->cp[j + 1] - S->cp[j]), 2.0);
    state.counters["flops_per_nnz"] = flops / std::max(1L, nnz);
    cs_ci_nfree(N);
    cs_ci_sfree(S);
  }
  state.counters["nnz_L"] = static_cast<double>(nnz);
}
void BM_FactorUpdatable(benchmark::State& state, BenchMesh* b) {
  const Eigen::SparseMatrix<Complex> A = shifted_stiffness(*b);
  long nnz = 0;
  for (auto _ : state) {
    UpdatableCholesky F(A);
    nnz = F.factor_nonzeros();
  }
  state.counters["nnz_L"] = static_cast<double>(nnz);
}

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
  // QUADCOVER_BENCH_PIPELINE=only: just the pipeline (no per-mesh setup of the other benchmarks).
  const char* pipeline = std::getenv("QUADCOVER_BENCH_PIPELINE");
  if (pipeline && std::string(pipeline) == "only") {
    for (const auto& p : paths)
      benchmark::RegisterBenchmark(("OptimizedPipeline/" + std::filesystem::path(p).stem().string()).c_str(),
                                   BM_OptimizedPipeline, p)
          ->Unit(benchmark::kSecond)
          ->Iterations(1)
          ->UseRealTime();
    paths.clear();
  }
  for (const auto& p : paths) {
    g_meshes.push_back(load(p));
    BenchMesh* b = g_meshes.back().get();
    benchmark::RegisterBenchmark(("FromScratch/" + b->name).c_str(), BM_FromScratch, b)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("ViaUpdates/" + b->name).c_str(), BM_ViaUpdates, b)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("FactorCxsparse/" + b->name).c_str(), BM_FactorCxsparse, b)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("FactorUpdatable/" + b->name).c_str(), BM_FactorUpdatable, b)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("PlainCXSparse/" + b->name).c_str(), BM_PlainCxsparse, b)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("ReachLimited/" + b->name).c_str(), BM_ReachLimited, b)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("LocalEstimate/" + b->name).c_str(), BM_LocalEstimate, b)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("EstimateBatch2/" + b->name).c_str(), BM_EstimateBatch2, b)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    if (std::getenv("QUADCOVER_BENCH_PIPELINE"))
      benchmark::RegisterBenchmark(("OptimizedPipeline/" + b->name).c_str(), BM_OptimizedPipeline, p)
          ->Unit(benchmark::kSecond)
          ->Iterations(1)
          ->UseRealTime();
  }
  if (std::getenv("QUADCOVER_BENCH_DECAY"))
    for (const auto& b : g_meshes) print_decay(*b);
  if (std::getenv("QUADCOVER_BENCH_SWEEP") && !g_meshes.empty()) {
    // Figure 6.5 (thesis 6.4) on the first mesh: one row per branch point count.
    BalancingSweepOptions o;
    o.optimize.max_evaluations = 0;
    o.max_rows =
        std::atoi(std::getenv("QUADCOVER_BENCH_SWEEP")) > 1 ? std::atoi(std::getenv("QUADCOVER_BENCH_SWEEP")) : 0;
    const auto t = Clock::now();
    const auto rows = balancing_sweep(g_meshes[0]->mesh, g_meshes[0]->field, o);
    std::printf(
        "Figure 6.5 sweep, %s (%.1f s)\n| branch points | E_D | E_H | E_D + E_H | h_sym |\n|---|---|---|---|---|\n",
        g_meshes[0]->name.c_str(), since(t));
    for (const auto& r : rows)
      std::printf("| %d | %.4f | %.3f | %.3f | %d |\n", r.branch_points, r.energy_curl, r.energy_harmonic, r.total,
                  r.h_sym);
  }
  benchmark::RegisterBenchmark("RoundingSearch3", BM_RoundingSearch3)
      ->Arg(100)
      ->Arg(200)
      ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
