// Thesis Table 7.1 on the Stanford bunny (tests/data/bunny_3k.obj) at about 6500 output vertices: the QuadCover
// pipeline (frame field → parameterization → [optimization] → extraction) and the regularity metrics of the
// result. `bench_table71 --table` prints the Markdown table of BENCHMARKS.md (section "Table 7.1"); without it the
// Google Benchmark timings of the stages run. Mesh: argv after --mesh, $QUADCOVER_BENCH_MESH, or bunny_3k.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "field/compute_frame_field.h"
#include "io/read_mesh.h"
#include "metrics/report.h"
#include "param/parameterize.h"
#include "quad/extract_quads.h"

namespace qc = quadcover;

namespace {

std::string mesh_path = std::string(QUADCOVER_SOURCE_DIR) + "/tests/data/bunny_3k.obj";
int target_vertices = 6500;

struct Column {
  std::string name;
  bool available = true;
  std::string note;
  qc::QuadQuality quads;
  qc::ParamQuality param;
  qc::ExtractionReport extraction;
  qc::SurfaceDistance distance;
  double seconds = 0;
};

qc::Mesh load() { return qc::build_mesh(qc::read_mesh(mesh_path)).mesh; }

// field → parameterization at density `quads` → extraction.
qc::ExtractionResult pipeline(const qc::Mesh& mesh, int quads, qc::Parameterization& P) {
  const qc::FrameField field = qc::compute_frame_field(mesh);
  qc::ParamOptions po;
  po.target_quads = quads;
  P = qc::parameterize(mesh, field, po);
  return qc::extract_quads(mesh, P);
}

// Plain QuadCover (thesis [KNP07]): curvature field, QuadCover parameterization on the rotated lattice, extraction.
// The density is calibrated once so that the output has about `target_vertices` vertices.
Column run_plain(const qc::Mesh& mesh) {
  Column c{"QuadCover"};
  qc::Parameterization P;
  const auto t0 = std::chrono::steady_clock::now();
  qc::ExtractionResult ex = pipeline(mesh, target_vertices, P);
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int first = ex.mesh.num_vertices();
  if (first > 0) {
    const int calibrated = static_cast<int>(std::lround(double(target_vertices) * target_vertices / first));
    ex = pipeline(mesh, calibrated, P);
  }
  c.param = qc::param_quality(mesh, P);
  c.extraction = ex.report;
  c.quads = qc::quad_quality(ex.mesh);
  c.distance = qc::surface_distance(ex.mesh.V, ex.mesh.faces, mesh.V(), mesh.F());
  return c;
}

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

void print_table(const std::vector<Column>& cols) {
  std::printf("| | thesis QuadCover | thesis Relocation | thesis Balancing |");
  for (const auto& c : cols) std::printf(" ours: %s |", c.name.c_str());
  std::printf("\n|---|---|---|---|");
  for (std::size_t i = 0; i < cols.size(); ++i) std::printf("---|");
  std::printf("\n");
  auto row = [&](const char* name, const char* thesis, auto value) {
    std::printf("| %s | %s |", name, thesis);
    for (const auto& c : cols) std::printf(" %s |", c.available ? value(c).c_str() : "n/a");
    std::printf("\n");
  };
  row("vertices", "6535 | 6464 | 6506", [](const Column& c) { return std::to_string(c.quads.vertices); });
  row("branch points", "37 | 59 | 93", [](const Column& c) { return std::to_string(c.param.branch_points); });
  row("irregular vertices", "– | – | –", [](const Column& c) { return std::to_string(c.quads.irregular_vertices); });
  row("RSD edge", "18.2% | 9.0% | 8.1%", [](const Column& c) { return fmt("%.1f%%", c.quads.rsd_edge_length); });
  row("RSD angle", "14.8% | 8.0% | 7.2%", [](const Column& c) { return fmt("%.1f%%", c.quads.rsd_corner_angle); });
  row("ARAP (normalized, see below)", "– | – | –", [](const Column& c) { return fmt("%.4f", c.param.arap); });
  row("flipped triangles of the map", "– | – | –",
      [](const Column& c) { return std::to_string(c.param.flipped_triangles); });
  row("untangled / cut out by extraction", "– | – | –", [](const Column& c) {
    return std::to_string(c.extraction.unfolded_triangles) + " / " +
           std::to_string(c.extraction.flipped_triangles + c.extraction.degenerate_triangles);
  });
  row("non-quad faces", "– | – | –", [](const Column& c) { return std::to_string(c.quads.non_quads); });
  row("closed manifold", "– | – | –", [](const Column& c) {
    return std::string(c.quads.topology.manifold() && c.quads.topology.closed() ? "yes" : "no");
  });
  row("max distance / bbox diag", "– | – | –", [](const Column& c) { return fmt("%.4f", c.distance.max); });
  row("seconds (one field+param+opt+extract run)", "– | – | –", [](const Column& c) { return fmt("%.2f", c.seconds); });
  for (const auto& c : cols)
    if (!c.available) std::printf("\n%s: %s\n", c.name.c_str(), c.note.c_str());
  if (std::getenv("QUADCOVER_BENCH_VERBOSE"))
    for (const auto& c : cols)
      if (c.available) {
        qc::Report r;
        r.input = c.name;
        r.parameterization = c.param;
        r.extraction = c.extraction;
        r.quad_mesh = c.quads;
        r.surface_distance = c.distance;
        std::fprintf(stderr, "%s\n", qc::to_json(r).dump(1).c_str());
      }
}

void BM_Extract(benchmark::State& state) {
  const qc::Mesh mesh = load();
  const qc::FrameField field = qc::compute_frame_field(mesh);
  qc::ParamOptions po;
  po.target_quads = static_cast<int>(state.range(0));
  const qc::Parameterization P = qc::parameterize(mesh, field, po);
  int quads = 0;
  for (auto _ : state) {
    const qc::ExtractionResult ex = qc::extract_quads(mesh, P);
    quads = ex.mesh.num_faces();
    benchmark::DoNotOptimize(quads);
  }
  state.counters["faces"] = quads;
}
BENCHMARK(BM_Extract)->Arg(6500)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  if (const char* m = std::getenv("QUADCOVER_BENCH_MESH")) mesh_path = m;
  bool table = false;
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--table")) table = true;
    else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc) mesh_path = argv[++i];
    else if (!std::strcmp(argv[i], "--vertices") && i + 1 < argc) target_vertices = std::atoi(argv[++i]);
    else rest.push_back(argv[i]);
  }
  if (table) {
    const qc::Mesh mesh = load();
    std::vector<Column> cols = {run_plain(mesh)};
    Column reloc{"Relocation"}, full{"Balancing"};
    reloc.available = full.available = false;
    reloc.note = full.note = "needs the optimization stage (thesis Algorithm 6.1), not in the library yet";
    cols.push_back(reloc);
    cols.push_back(full);
    print_table(cols);
    return 0;
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
