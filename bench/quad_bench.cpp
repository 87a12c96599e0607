// Quad extraction timings (issue 7: near-linear, a 100k-quad output in a few seconds).
//  - ExtractTorus/<quads>: a synthetic seamless torus map (translational seams, no cones, no folds) on a fixed
//    torus mesh of 2·240·120 triangles, P×Q unit cells; the output is exactly P·Q quads. Time per output quad shows
//    the scaling in
//    the output size (counter quads_per_s).
//  - ExtractMesh/<quads>: the real pipeline input: field → parameterize at that many target quads (computed once,
//    not timed) → extract_quads (timed, with collapse + fold repair). Mesh: the first non-flag argument, else
//    $QUADCOVER_BENCH_MESH, else tests/data/bunny_20k_holes.obj.
//  - SmoothMesh/<quads>: tangential smoothing (smooth_quads, 20 rounds: the remesh default) of that extraction,
//    from a copy each time (the copy is timed too; it is small against a round).
//   bench_quad [--benchmark_flags...] [mesh]
#include <benchmark/benchmark.h>

#include "bench_mesh_path.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <numbers>
#include <string>

#include "field/compute_frame_field.h"
#include "io/read_mesh.h"
#include "param/parameterize.h"
#include "quad/extract_quads.h"
#include "quad/smooth_quads.h"
#include "quad/transitions.h"

namespace {

using namespace quadcover;

std::string g_mesh_path;

// Torus (R = 2, r = 0.7) with nM × nm vertex grid, each cell split into two triangles, and the map
// φ(i, j) = (P i / nM + 0.31, Q j / nm + 0.17) read per corner (so the period seams carry translations P and iQ).
struct TorusMap {
  Mesh mesh;
  Parameterization param;
};
TorusMap make_torus_map(int nM, int nm, int P, int Q) {
  Eigen::MatrixX3d V(nM * nm, 3);
  for (int i = 0; i < nM; ++i)
    for (int j = 0; j < nm; ++j) {
      const double u = 2 * std::numbers::pi * i / nM, v = 2 * std::numbers::pi * j / nm;
      V.row(i * nm + j) << (2 + 0.7 * std::cos(v)) * std::cos(u), (2 + 0.7 * std::cos(v)) * std::sin(u),
          0.7 * std::sin(v);
    }
  Eigen::MatrixX3i F(2 * nM * nm, 3);
  Eigen::MatrixX3cd uv(2 * nM * nm, 3);
  auto id = [&](int i, int j) { return (i % nM) * nm + (j % nm); };
  auto phi = [&](int i, int j) { return Complex(double(P) * i / nM + 0.31, double(Q) * j / nm + 0.17); };
  for (int i = 0; i < nM; ++i)
    for (int j = 0; j < nm; ++j) {
      const int q = 2 * (i * nm + j);
      F.row(q) << id(i, j), id(i + 1, j), id(i + 1, j + 1);
      F.row(q + 1) << id(i, j), id(i + 1, j + 1), id(i, j + 1);
      uv.row(q) << phi(i, j), phi(i + 1, j), phi(i + 1, j + 1);
      uv.row(q + 1) << phi(i, j), phi(i + 1, j + 1), phi(i, j + 1);
    }
  TorusMap t{Mesh::from_triangles(V, F), {}};
  t.param = parameterization_from_uv(t.mesh, uv);
  return t;
}

void BM_ExtractTorus(benchmark::State& state) {
  static const TorusMap* cached = nullptr;
  static int cached_quads = -1;
  const int quads = static_cast<int>(state.range(0));
  static TorusMap t;
  if (cached_quads != quads) {
    const int Q = static_cast<int>(std::lround(std::sqrt(quads / 2.0))), P = quads / Q;  // cells ≈ 2:1 like the mesh
    t = make_torus_map(240, 120, P, Q);
    cached = &t;
    cached_quads = quads;
  }
  ExtractionResult r;
  for (auto _ : state) r = extract_quads(cached->mesh, cached->param);
  state.counters["faces_in"] = cached->mesh.num_faces();
  state.counters["quads"] = r.report.quads;
  state.counters["non_quads"] = r.report.non_quads;
  state.counters["quads_per_s"] = benchmark::Counter(r.report.quads, benchmark::Counter::kIsIterationInvariantRate);
}

const Mesh& bench_mesh() {
  static const Mesh mesh = build_mesh(read_mesh(g_mesh_path)).mesh;
  return mesh;
}

// The bench mesh's map at `target` quads (computed once per target).
const Parameterization& bench_param(long target) {
  static std::map<long, Parameterization> params;
  if (!params.count(target)) {
    ParamOptions po;
    po.density.target_quads = static_cast<int>(target);
    params[target] = parameterize(bench_mesh(), compute_frame_field(bench_mesh()), po);
  }
  return params[target];
}

void BM_ExtractMesh(benchmark::State& state) {
  const Parameterization& P = bench_param(state.range(0));
  ExtractionResult r;
  for (auto _ : state) r = extract_quads(bench_mesh(), P);
  const ExtractionReport& x = r.report;
  state.counters["faces_in"] = bench_mesh().num_faces();
  state.counters["quads"] = x.quads;
  state.counters["non_quads"] = x.non_quads;
  state.counters["flipped_in"] = x.unfolded_triangles + x.flipped_triangles;
  state.counters["left_flipped"] = x.flipped_triangles + x.degenerate_triangles;
  state.counters["collapsed"] = x.collapsed_edges;
  state.counters["quads_per_s"] = benchmark::Counter(x.quads, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_SmoothMesh(benchmark::State& state) {
  const Parameterization& P = bench_param(state.range(0));
  const ExtractionResult ex = extract_quads(bench_mesh(), P);
  QuadSmoothingReport r;
  for (auto _ : state) {
    QuadMesh q = ex.mesh;
    r = smooth_quads(q, bench_mesh(), P, {});
  }
  state.counters["quads"] = ex.report.quads;
  state.counters["rejected_moves"] = r.rejected_moves;
  state.counters["quads_per_s"] = benchmark::Counter(ex.report.quads, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  g_mesh_path = bench_mesh_path(argc, argv);
  try {
    benchmark::AddCustomContext("mesh", g_mesh_path);
    benchmark::AddCustomContext("mesh_faces", std::to_string(bench_mesh().num_faces()));
  } catch (const std::exception& e) {
    std::cerr << "bench_quad: " << e.what() << "\n";
    return 2;
  }
  benchmark::RegisterBenchmark("ExtractTorus", BM_ExtractTorus)
      ->Arg(10000)
      ->Arg(100000)
      ->Arg(400000)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("ExtractMesh", BM_ExtractMesh)
      ->Arg(2000)
      ->Arg(20000)
      ->Arg(100000)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("SmoothMesh", BM_SmoothMesh)
      ->Arg(2000)
      ->Arg(20000)
      ->Arg(100000)
      ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
