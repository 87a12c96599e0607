// Parameterization timings (thesis 2.4, 4): the QuadCover pipeline per stage — cut through B and gauge, curl
// removal (𝔏̄* assembly + complex Cholesky + solve), integration, rounding, harmonic correction (𝔏̄), assembly —
// on a curvature field computed once. The field stage is timed separately for context.
// Mesh: the first non-flag argument, else $QUADCOVER_BENCH_MESH, else tests/data/bunny_20k_holes.obj.
//   bench_param [--benchmark_flags...] [mesh]        e.g. bench_param /work/shared/meshes/armadillo_86k.obj
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cstdlib>
#include <iostream>
#include <map>
#include <string>

#include "bench_mesh_path.h"
#include "cover/complex_stiffness.h"
#include "field/compute_frame_field.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"
#include "param/cover_cut.h"
#include "param/parameterize.h"
#include "param/period_matrix.h"
#include "param/seams.h"

namespace {

using namespace quadcover;

std::string g_mesh_path;

const Mesh& bench_mesh() {
  static const Mesh mesh = build_mesh(read_mesh(g_mesh_path)).mesh;
  return mesh;
}
const FrameField& bench_field() {
  static const FrameField field = compute_frame_field(bench_mesh());
  return field;
}

void BM_Field(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(compute_frame_field(bench_mesh()));
  state.counters["faces"] = bench_mesh().num_faces();
}

void BM_CoverCut(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(build_cover_cut(bench_mesh(), bench_field().matching));
}

// The period matrix (6.3.2) alone on the factor of 𝔏̄ (factored once, not timed): one solve per free path in blocks
// of 32, ⟨∇u_a, Σ_b⟩ from the sparse right-hand sides.
void BM_PeriodMatrix(benchmark::State& state) {
  const CoverCut cc = build_cover_cut(bench_mesh(), bench_field().matching);
  const HarmonicCorrection hc(bench_mesh(), cc,
                              std::vector<char>(static_cast<std::size_t>(bench_mesh().num_components()), 0));
  PeriodMatrix pm;
  for (auto _ : state) pm = period_matrix(bench_mesh(), cc, hc);
  state.counters["paths"] = static_cast<double>(pm.paths.size());
  state.counters["sigma_support"] = static_cast<double>(pm.sigma_support);
}

// The whole plain pipeline with range(0) ARAP relaxation rounds (0 = off, 20 = default); each stage's mean wall
// time is reported as a counter (ms), and the flipped triangles of the result.
void BM_Parameterize(benchmark::State& state) {
  std::map<std::string, double> total;
  Parameterization P;
  ParamOptions options;
  options.relaxation.iterations = static_cast<int>(state.range(0));
  for (auto _ : state) {
    P = parameterize(bench_mesh(), bench_field(), options);
    for (const auto& [stage, s] : P.diagnostics.stage_seconds) total[stage] += s;
  }
  for (const auto& [stage, s] : total) state.counters[stage + "_ms"] = 1e3 * s / state.iterations();
  state.counters["faces"] = bench_mesh().num_faces();
  state.counters["branch_points"] = static_cast<double>(P.branch_points.size());
  state.counters["h_sym"] = P.h_sym;
  state.counters["flipped"] = flipped_triangles(bench_mesh(), P.uv).flipped;
}

// One check of a map on the whole mesh, as the untangling does after every Newton step and the relaxation after
// every round: per-corner values of a vertex function (layered_values) and the non-positive triangles of the
// result, on range(0) threads (the same run measures 1 and 2).
void BM_MapCheck(benchmark::State& state) {
  const Mesh& mesh = bench_mesh();
  const VertexLayers layers = vertex_layers(mesh, bench_field().matching);
  Eigen::VectorXcd u(mesh.num_vertices());
  for (int p = 0; p < mesh.num_vertices(); ++p) u[p] = Complex(mesh.V()(p, 0), mesh.V()(p, 1));
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(0)));
  int non_positive = 0;
  for (auto _ : state) non_positive = flipped_triangles(mesh, layered_values(mesh, layers, u)).non_positive;
  state.counters["faces"] = mesh.num_faces();
  state.counters["non_positive"] = non_positive;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  g_mesh_path = bench_mesh_path(argc, argv);
  try {
    benchmark::AddCustomContext("mesh", g_mesh_path);
    benchmark::AddCustomContext("mesh_faces", std::to_string(bench_mesh().num_faces()));
    bench_field();
  } catch (const std::exception& e) {
    std::cerr << "bench_param: " << e.what() << "\n";
    return 2;
  }
  benchmark::RegisterBenchmark("Field", BM_Field)->Unit(benchmark::kMillisecond)->Iterations(1);
  benchmark::RegisterBenchmark("CoverCut", BM_CoverCut)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("PeriodMatrix", BM_PeriodMatrix)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Parameterize", BM_Parameterize)
      ->ArgName("relaxation")
      ->Arg(RelaxationOptions{}.iterations)
      ->Arg(0)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("MapCheck", BM_MapCheck)
      ->ArgName("threads")
      ->Arg(1)
      ->Arg(2)
      ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
