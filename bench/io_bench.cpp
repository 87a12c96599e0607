// Loading timings (issue 3 "Performance", issue 8 "1M-face mesh"): read + validate + connectivity/geometry
// (build_mesh) on a mesh file, each step alone and together, in faces per second; plus a generated 1M-face
// torus written to OBJ and loaded, with the peak resident memory.
// Mesh: the first non-flag argument, else $QUADCOVER_BENCH_MESH, else tests/data/bunny_20k_holes.obj.
//   bench_io [--benchmark_flags...] [mesh.obj|off|ply|stl]
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <string>
#include <sys/resource.h>
#include <unistd.h>

#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "mesh/mesh.h"

namespace {

using namespace quadcover;

std::string g_mesh_path;

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

void set_rate(benchmark::State& state, std::size_t faces) {
  state.counters["faces"] = static_cast<double>(faces);
  state.counters["faces_per_second"] =
      benchmark::Counter(static_cast<double>(faces), benchmark::Counter::kIsIterationInvariantRate);
}

const PolygonSoup& bench_soup() {
  static const PolygonSoup soup = read_mesh(g_mesh_path);
  return soup;
}

void BM_Read(benchmark::State& state) {
  std::size_t faces = 0;
  for (auto _ : state) {
    const PolygonSoup soup = read_mesh(g_mesh_path);
    faces = soup.num_faces();
    benchmark::DoNotOptimize(soup.positions.data());
  }
  set_rate(state, faces);
}

void BM_Validate(benchmark::State& state) {
  const PolygonSoup& soup = bench_soup();
  for (auto _ : state) {
    const ValidationReport report = validate(soup);
    benchmark::DoNotOptimize(report.problems.size());
  }
  set_rate(state, soup.num_faces());
}

// Validation + connectivity + cached geometry.
void BM_BuildMesh(benchmark::State& state) {
  const PolygonSoup& soup = bench_soup();
  for (auto _ : state) {
    const MeshBuildResult built = build_mesh(soup);
    benchmark::DoNotOptimize(built.mesh.num_edges());
  }
  set_rate(state, soup.num_faces());
}

// The whole load as the CLI does it: file -> validated Mesh.
void BM_LoadValidateBuild(benchmark::State& state) {
  std::size_t faces = 0;
  for (auto _ : state) {
    const MeshBuildResult built = build_mesh(read_mesh(g_mesh_path));
    faces = static_cast<std::size_t>(built.mesh.num_faces());
    benchmark::DoNotOptimize(built.mesh.num_edges());
  }
  set_rate(state, faces);
  state.counters["peak_rss_mb"] = peak_rss_mb();
}

// A torus with n_major × n_minor quads (2 n_major n_minor triangles), written once as OBJ to the temp dir.
std::string generated_torus_obj(int n_major, int n_minor) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("quadcover_bench_torus_" + std::to_string(2L * n_major * n_minor) + "_" +
                             std::to_string(::getpid()) + ".obj"))
                               .string();
  Eigen::MatrixX3d V(static_cast<Eigen::Index>(n_major) * n_minor, 3);
  Eigen::MatrixX3i F(2 * static_cast<Eigen::Index>(n_major) * n_minor, 3);
  auto id = [&](int i, int j) { return ((i + n_major) % n_major) * n_minor + (j + n_minor) % n_minor; };
  for (int i = 0; i < n_major; ++i)
    for (int j = 0; j < n_minor; ++j) {
      const double u = 2 * std::numbers::pi * i / n_major, v = 2 * std::numbers::pi * j / n_minor;
      V.row(id(i, j)) << (2 + 0.7 * std::cos(v)) * std::cos(u), (2 + 0.7 * std::cos(v)) * std::sin(u), 0.7 * std::sin(v);
      const Eigen::Index q = 2 * (static_cast<Eigen::Index>(i) * n_minor + j);
      F.row(q) << id(i, j), id(i + 1, j), id(i + 1, j + 1);
      F.row(q + 1) << id(i, j), id(i + 1, j + 1), id(i, j + 1);
    }
  // Round to 7 significant digits like typical scanned/exported OBJ files (full precision would be 17).
  V = (V.array() * 1e6).round() / 1e6;
  write_obj(path, V, F);
  return path;
}

void BM_GeneratedTorus(benchmark::State& state) {
  const int n_major = static_cast<int>(state.range(0)), n_minor = static_cast<int>(state.range(1));
  const std::string path = generated_torus_obj(n_major, n_minor);
  std::size_t faces = 0;
  int genus = -1;
  for (auto _ : state) {
    const MeshBuildResult built = build_mesh(read_mesh(path));
    faces = static_cast<std::size_t>(built.mesh.num_faces());
    genus = built.mesh.genus();
    benchmark::DoNotOptimize(built.mesh.num_edges());
  }
  std::filesystem::remove(path);
  if (genus != 1) state.SkipWithError("generated torus did not come back as genus 1");
  set_rate(state, faces);
  state.counters["peak_rss_mb"] = peak_rss_mb();
}

/// A closed bipyramid whose two apexes have valence n: the connectivity must stay linear in the valence
/// (tests/mesh/adversarial_test.cpp checks the result; this measures the cost, with the complexity fit).
void BM_HighValenceFan(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Eigen::MatrixX3d V(n + 2, 3);
  Eigen::MatrixX3i F(2 * n, 3);
  V.row(0) << 0, 0, 0.3;
  V.row(n + 1) << 0, 0, -0.3;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n;
    V.row(k + 1) << std::cos(a), std::sin(a), 0;
    const int next = (k + 1) % n + 1;
    F.row(2 * k) << 0, k + 1, next;
    F.row(2 * k + 1) << n + 1, next, k + 1;
  }
  for (auto _ : state) {
    const Mesh mesh = Mesh::from_triangles(V, F);
    benchmark::DoNotOptimize(mesh.valence(0));
  }
  state.SetComplexityN(n);
}

}  // namespace

BENCHMARK(BM_HighValenceFan)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)->Complexity();
BENCHMARK(BM_Read)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Validate)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BuildMesh)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LoadValidateBuild)->Unit(benchmark::kMillisecond);
// 350,000 and 1,000,000 faces.
BENCHMARK(BM_GeneratedTorus)->Args({700, 250})->Args({1000, 500})->Unit(benchmark::kMillisecond)->Iterations(3);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  for (int i = 1; i < argc; ++i)
    if (argv[i][0] != '-') g_mesh_path = argv[i];
  if (g_mesh_path.empty()) {
    const char* env = std::getenv("QUADCOVER_BENCH_MESH");
    g_mesh_path = env ? env : std::string(QUADCOVER_SOURCE_DIR) + "/tests/data/bunny_20k_holes.obj";
  }
  std::cerr << "bench_io: mesh " << g_mesh_path << "\n";
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
