// Calculus timings (thesis 1.2.4): assembling 𝔏 and 𝔏*, factorizing them once (HodgeDecomposer), and one Hodge
// decomposition with the factors reused, for the CHOLMOD and the Eigen backend in the same run.
// Mesh: the first non-flag argument, else $QUADCOVER_BENCH_MESH, else tests/data/bunny_20k_holes.obj.
//   bench_calculus [--benchmark_flags...] [mesh]
#include <benchmark/benchmark.h>

#include "bench_mesh_path.h"

#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>

#include "calculus/hodge.h"
#include "calculus/stiffness.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"

namespace {

using namespace quadcover;

std::string g_mesh_path;

const Mesh& bench_mesh() {
  static const Mesh mesh = build_mesh(read_mesh(g_mesh_path)).mesh;
  return mesh;
}

VectorField bench_field(const Mesh& mesh) {  // deterministic, smooth-ish: the tangential part of a rotating field
  VectorField X(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d c =
        (mesh.V().row(mesh.F()(f, 0)) + mesh.V().row(mesh.F()(f, 1)) + mesh.V().row(mesh.F()(f, 2))).transpose() / 3.0;
    X[f] = mesh.to_local(f, Eigen::Vector3d(-c.y(), c.x(), 0.3) + Eigen::Vector3d(std::sin(7 * c.z()), 0, 0));
  }
  return X;
}

void set_counters(benchmark::State& state, const Mesh& mesh) {
  state.counters["faces"] = mesh.num_faces();
  state.counters["vertices"] = mesh.num_vertices();
  state.counters["edges"] = mesh.num_edges();
}

void BM_AssembleStiffness(benchmark::State& state) {
  const Mesh& mesh = bench_mesh();
  for (auto _ : state) {
    auto L = conforming_stiffness(mesh);
    auto Ls = nonconforming_stiffness(mesh);
    benchmark::DoNotOptimize(L.nonZeros() + Ls.nonZeros());
  }
  set_counters(state, mesh);
}

// Reduced 𝔏 and 𝔏*: symbolic analysis + numeric factorization of both.
void BM_Factorize(benchmark::State& state, CholeskyBackend backend) {
  const Mesh& mesh = bench_mesh();
  for (auto _ : state) {
    HodgeDecomposer hodge(mesh, {backend});
    benchmark::DoNotOptimize(&hodge);
  }
  set_counters(state, mesh);
}

// One decomposition X = X_P + X_C + X_H with the factors reused: div, curl*, two solves, gradients.
void BM_Decompose(benchmark::State& state, CholeskyBackend backend) {
  const Mesh& mesh = bench_mesh();
  const HodgeDecomposer hodge(mesh, {backend});
  const VectorField X = bench_field(mesh);
  for (auto _ : state) {
    HodgeParts parts = hodge.decompose(X);
    benchmark::DoNotOptimize(parts.harmonic.data());
  }
  set_counters(state, mesh);
}

// Factorization + one decomposition: the cost of the first Hodge decomposition on a new mesh.
void BM_FactorizeAndDecompose(benchmark::State& state, CholeskyBackend backend) {
  const Mesh& mesh = bench_mesh();
  const VectorField X = bench_field(mesh);
  for (auto _ : state) {
    HodgeDecomposer hodge(mesh, {backend});
    HodgeParts parts = hodge.decompose(X);
    benchmark::DoNotOptimize(parts.harmonic.data());
  }
  set_counters(state, mesh);
}

void register_benchmarks() {
  benchmark::RegisterBenchmark("AssembleStiffness", BM_AssembleStiffness)->Unit(benchmark::kMillisecond);
  struct Named {
    const char* name;
    CholeskyBackend backend;
  };
  std::vector<Named> backends;
  if (SparseCholesky<double>::cholmod_available()) backends.push_back({"cholmod", CholeskyBackend::Cholmod});
  backends.push_back({"eigen", CholeskyBackend::Eigen});
  for (const Named& b : backends) {
    benchmark::RegisterBenchmark((std::string("Factorize/") + b.name).c_str(), BM_Factorize, b.backend)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((std::string("Decompose/") + b.name).c_str(), BM_Decompose, b.backend)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((std::string("FactorizeAndDecompose/") + b.name).c_str(), BM_FactorizeAndDecompose,
                                 b.backend)
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  g_mesh_path = bench_mesh_path(argc, argv);
  try {
    const Mesh& mesh = bench_mesh();
    benchmark::AddCustomContext("mesh", g_mesh_path);
    benchmark::AddCustomContext("mesh_faces", std::to_string(mesh.num_faces()));
  } catch (const std::exception& e) {
    std::cerr << "bench_calculus: " << e.what() << "\n";
    return 2;
  }
  register_benchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
