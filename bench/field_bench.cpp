// Frame field timings (thesis Chapter 5): principal curvature frames (HP, CSM), stability + trusted selection +
// propagation, assembling and factoring the smoothing system (5.4), one solve, one re-solve after a matching
// change (5.2.2: a right-hand-side update and two triangular solves, no factorization), the power-field fill
// (linear solve alone and with the default Ginzburg–Landau steps), and the whole pipeline with either fill.
// Meshes: the non-flag arguments, else the ':'-separated list in $QUADCOVER_BENCH_MESHES, else
// tests/data/bunny_20k_holes.obj plus $QUADCOVER_BENCH_MESH if set (e.g. /work/shared/meshes/armadillo_86k.obj).
//   bench_field [--benchmark_flags...] [mesh...]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "field/compute_frame_field.h"
#include "field/matching.h"
#include "field/power_field.h"
#include "field/propagation.h"
#include "field/smoothing.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"

namespace {

using namespace quadcover;

struct BenchMesh {
  std::string name;
  Mesh mesh;
  // Inputs of the later stages, computed once.
  CurvatureFrames frames;
  Eigen::VectorXd stability;
  std::vector<char> trusted;
  FrameField propagated;
};

std::vector<std::unique_ptr<BenchMesh>> g_meshes;

std::unique_ptr<BenchMesh> load(const std::string& path) {
  auto b = std::make_unique<BenchMesh>();
  b->name = std::filesystem::path(path).stem().string();
  b->mesh = build_mesh(read_mesh(path)).mesh;
  b->frames = principal_curvature_frames(b->mesh);
  const Eigen::VectorXd theta =
      field_curvature(b->mesh, cross_field_with_straightest_matching(b->mesh, b->frames.direction));
  b->stability = stability_weights(b->mesh, b->frames, theta);
  b->trusted = select_trusted(b->mesh, b->stability, 0.2);
  b->propagated = cross_field_with_straightest_matching(
      b->mesh, propagate_frames(b->mesh, b->frames.direction, b->trusted, b->stability));
  return b;
}

void counters(benchmark::State& state, const BenchMesh& b) { state.counters["faces"] = b.mesh.num_faces(); }

void BM_Curvature(benchmark::State& state, const BenchMesh* b, CurvatureMethod method) {
  for (auto _ : state) {
    CurvatureFrames f = principal_curvature_frames(b->mesh, {method});
    benchmark::DoNotOptimize(f.direction.data());
  }
  counters(state, *b);
}

// Matching (5.1), stability (5.2), trusted selection and breadth-first propagation (5.1.2).
void BM_Propagation(benchmark::State& state, const BenchMesh* b) {
  for (auto _ : state) {
    const Eigen::VectorXd theta =
        field_curvature(b->mesh, cross_field_with_straightest_matching(b->mesh, b->frames.direction));
    const Eigen::VectorXd w = stability_weights(b->mesh, b->frames, theta);
    const std::vector<char> trusted = select_trusted(b->mesh, w, 0.2);
    Eigen::VectorXcd X = propagate_frames(b->mesh, b->frames.direction, trusted, w);
    benchmark::DoNotOptimize(X.data());
  }
  counters(state, *b);
}

// Assembly of A and b (5.4) and the Cholesky factorization of A.
void BM_SmoothingFactor(benchmark::State& state, const BenchMesh* b) {
  for (auto _ : state) {
    FrameSmoother s(b->mesh, b->propagated, b->stability, b->trusted, {}, 0.5);
    benchmark::DoNotOptimize(&s);
  }
  counters(state, *b);
}

void BM_SmoothingSolve(benchmark::State& state, const BenchMesh* b) {
  const FrameSmoother s(b->mesh, b->propagated, b->stability, b->trusted, {}, 0.5);
  for (auto _ : state) {
    Eigen::VectorXd alpha = s.solve();
    benchmark::DoNotOptimize(alpha.data());
  }
  counters(state, *b);
}

// 5.2.2: change one edge's matching (alternately +1 and -1, so the state stays bounded) and re-solve.
void BM_ResolveAfterMatchingChange(benchmark::State& state, const BenchMesh* b) {
  FrameSmoother s(b->mesh, b->propagated, b->stability, b->trusted, {}, 0.5);
  int e = 0, sign = 1;
  while (b->mesh.is_boundary_edge(e)) ++e;
  for (auto _ : state) {
    s.change_matching(e, sign);
    sign = -sign;
    Eigen::VectorXd alpha = s.solve();
    benchmark::DoNotOptimize(alpha.data());
  }
  counters(state, *b);
}

// The smooth fill: assembly, factorization and solve of the power-field system with the default options of
// compute_frame_field (trusted faces aligned with weight ω^stable, no feature constraints here); `steps`
// Ginzburg–Landau steps on top (one refactorization, then two triangular solves each).
void BM_PowerFill(benchmark::State& state, const BenchMesh* b, int steps) {
  PowerFieldProblem p;
  p.target = b->frames.direction;
  p.weight = Eigen::VectorXd::Zero(b->mesh.num_faces());
  for (int t = 0; t < b->mesh.num_faces(); ++t)
    if (b->trusted[static_cast<std::size_t>(t)]) p.weight[t] = b->stability[t];
  p.weight /= p.weight.sum() / static_cast<double>(std::count(b->trusted.begin(), b->trusted.end(), 1));
  p.alignment = FieldOptions{}.fill_alignment;
  p.unit_weight = FieldOptions{}.fill_unit_weight;
  p.iterations = steps;
  for (auto _ : state) {
    PowerFieldResult r = smooth_power_field(b->mesh, p);
    benchmark::DoNotOptimize(r.X.data());
  }
  counters(state, *b);
}

void BM_Pipeline(benchmark::State& state, const BenchMesh* b, Fill fill) {
  FieldOptions options;
  options.fill = fill;
  for (auto _ : state) {
    FrameFieldResult r = compute_frame_field_detailed(b->mesh, options);
    benchmark::DoNotOptimize(r.field.X.data());
  }
  counters(state, *b);
}

void register_benchmarks() {
  for (const auto& m : g_meshes) {
    const BenchMesh* b = m.get();
    const auto reg = [&](const std::string& what, auto fn, auto... args) {
      benchmark::RegisterBenchmark((what + "/" + b->name).c_str(), fn, b, args...)->Unit(benchmark::kMillisecond);
    };
    reg("CurvatureHP", BM_Curvature, CurvatureMethod::HildebrandtPolthier);
    reg("CurvatureCSM", BM_Curvature, CurvatureMethod::CohenSteinerMorvan);
    reg("Propagation", BM_Propagation);
    reg("SmoothingFactor", BM_SmoothingFactor);
    reg("SmoothingSolve", BM_SmoothingSolve);
    reg("ResolveAfterMatchingChange", BM_ResolveAfterMatchingChange);
    reg("PowerFillLinear", BM_PowerFill, 0);
    reg("PowerFillGL", BM_PowerFill, FieldOptions{}.fill_iterations);
    reg("PipelinePropagate", BM_Pipeline, Fill::Propagate);
    reg("PipelineSmooth", BM_Pipeline, Fill::Smooth);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  std::vector<std::string> paths(argv + 1, argv + argc);
  if (paths.empty()) {
    if (const char* list = std::getenv("QUADCOVER_BENCH_MESHES"); list && *list) {
      std::string s = list;
      for (std::size_t start = 0, end; start <= s.size(); start = end + 1) {
        end = s.find(':', start);
        if (end == std::string::npos) end = s.size();
        if (end > start) paths.push_back(s.substr(start, end - start));
      }
    } else {
      paths.push_back(std::string(QUADCOVER_SOURCE_DIR) + "/tests/data/bunny_20k_holes.obj");
      if (const char* extra = std::getenv("QUADCOVER_BENCH_MESH"); extra && *extra) paths.push_back(extra);
    }
  }
  try {
    for (const auto& p : paths) {
      g_meshes.push_back(load(p));
      benchmark::AddCustomContext("mesh_" + g_meshes.back()->name,
                                  p + " (" + std::to_string(g_meshes.back()->mesh.num_faces()) + " faces)");
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_field: " << e.what() << "\n";
    return 2;
  }
  register_benchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
