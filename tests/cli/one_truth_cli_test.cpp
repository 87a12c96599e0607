// Issue 18 items 7, 8, 9 and 16 through the real binary: one count of the topology (`info`, `metrics` and the
// remesh report agree), one count of cones and flipped/collapsed triangles (`param`, `metrics`, `render`), degraded
// results said on stderr even with -q, and vertex numbers that survive unreferenced vertices.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "mesh/surface_counts.h"
#include "param/seams.h"
#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

namespace fs = std::filesystem;
using quadcover::testing::CliRun;

class OneTruthCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::fresh_dir("one_truth_cli", ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  CliRun run(const std::string& args) const { return testing::run_cli(args, path("stderr.txt"), 300); }
  nlohmann::json json_of(const std::string& args) const {
    const CliRun r = run(args + " --json");
    EXPECT_TRUE(r.code == 0 || r.code == 2) << args << ": " << r.err;
    return nlohmann::json::parse(r.out.empty() ? "null" : r.out);
  }
  fs::path dir_;
};

/// The topology keys `info`, `metrics` and the reports all print.
constexpr const char* kTopologyKeys[] = {"components", "boundary_loops", "genus", "euler_characteristic",
                                         "manifold",   "oriented",       "closed"};

/// The faces of a soup as index lists.
std::vector<std::vector<int>> faces_of(const PolygonSoup& soup) { return soup_polygons(soup); }

/// A closed ellipsoid with one sliver: the first triangle (a, b, c) is split at a point m, 1e-12 outside the middle of
/// ab, into (a, m, c), (m, b, c) and the sliver (a, b, m) of relative height about 1e-11.
void write_sliver_ellipsoid(const std::string& file) {
  const Mesh e = testing::make_ellipsoid(3, 1.0, 0.8, 0.6);
  Eigen::MatrixX3d V(e.num_vertices() + 1, 3);
  V.topRows(e.num_vertices()) = e.V();
  Eigen::MatrixX3i F(e.num_faces() + 2, 3);
  F.topRows(e.num_faces()) = e.F();
  const int a = e.F()(0, 0), b = e.F()(0, 1), c = e.F()(0, 2), m = e.num_vertices();
  const Eigen::RowVector3d mid = 0.5 * (e.V().row(a) + e.V().row(b));
  V.row(m) = mid + 1e-12 * (mid - e.V().row(c)).normalized();
  F.row(0) << a, m, c;
  F.row(e.num_faces()) << m, b, c;
  F.row(e.num_faces() + 1) << a, b, m;
  write_obj(file, V, F);
}

// Item 7: a polygon mesh with a boundary, a 9-gon and a non-manifold vertex (a 2×2 quad grid and a 9-gon that
// touches it at one corner) gets the same numbers from `info`, `metrics` and surface_counts (the function behind
// every report's surface_check), and those numbers are its topology.
TEST_F(OneTruthCli, InfoMetricsAndReportsCountTheSameTopology) {
  {
    std::ofstream out(path("poly.obj"));
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) out << "v " << i << " " << j << " 0\n";
    for (int k = 1; k < 9; ++k) {  // the 9-gon around (3, 3): vertex 9 of the grid and 8 more
      const double t = 2 * std::numbers::pi * k / 9 - 3 * std::numbers::pi / 4;
      out << "v " << 3 + std::sqrt(2.0) * std::cos(t) << " " << 3 + std::sqrt(2.0) * std::sin(t) << " 0\n";
    }
    out << "f 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\nf 5 6 9 8\nf 9";
    for (int k = 10; k <= 17; ++k) out << " " << k;
    out << "\n";
  }
  const SurfaceCounts c = surface_counts(17, faces_of(read_mesh(path("poly.obj"))));
  EXPECT_EQ(c.components, 1);
  EXPECT_EQ(c.boundary_loops, 2);  // one per fan at the pinched vertex
  EXPECT_EQ(c.non_manifold_vertices, 1);
  EXPECT_EQ(c.non_manifold_edges, 0);
  EXPECT_EQ(c.non_quads, 1);
  EXPECT_EQ(c.edges, 12 + 9);
  EXPECT_EQ(c.euler_characteristic, 17 - 21 + 5);
  EXPECT_FALSE(c.manifold());
  EXPECT_TRUE(c.oriented());
  EXPECT_EQ(c.genus, -1);
  const nlohmann::json counted = to_json(c);
  const nlohmann::json info = json_of("info " + path("poly.obj"));
  const nlohmann::json metrics = json_of("metrics " + path("poly.obj"))["quad_mesh"];  // --json: the full report
  json_of("metrics " + path("poly.obj") + " --report " + path("m.json"));
  std::ifstream in(path("m.json"));
  const nlohmann::json report = nlohmann::json::parse(in)["quad_mesh"];
  for (const char* key : kTopologyKeys) {
    EXPECT_EQ(info[key], counted[key]) << "info " << key;
    EXPECT_EQ(metrics[key], counted[key]) << "metrics " << key;
    EXPECT_EQ(report[key], counted[key]) << "metrics --report " << key;
  }
  for (const char* key : {"vertices", "faces", "non_quads"}) {
    EXPECT_EQ(info[key], counted[key]) << key;
    EXPECT_EQ(metrics[key], counted[key]) << key;
  }
  EXPECT_EQ(info["non_manifold_vertices"], 1);
  EXPECT_EQ(report["non_manifold_vertices"], 1);
  // A valid triangle mesh: the same code gives the Mesh's own counts.
  const Mesh holes = testing::load_test_mesh("mech_holes_shark");
  const SurfaceCounts h = surface_counts(holes);
  EXPECT_EQ(h.boundary_loops, holes.num_boundary_loops());
  EXPECT_EQ(h.components, holes.num_components());
  EXPECT_EQ(h.genus, holes.genus());
  EXPECT_EQ(h.euler_characteristic, holes.euler_characteristic());
  // A Klein bottle is a manifold that cannot be oriented: info and metrics agree on both.
  const std::string klein = testing::data_path("bad/torus_klein_nonorientable");
  const nlohmann::json ki = json_of("info " + klein), km = json_of("metrics " + klein)["quad_mesh"];
  EXPECT_EQ(ki["manifold"], true);
  EXPECT_EQ(ki["orientable"], false);
  for (const char* key : kTopologyKeys) EXPECT_EQ(ki[key], km[key]) << "klein " << key;
}

// Item 7, remesh: the report's surface_check counts the written quad mesh as `info` and `metrics` do, and a closed
// input whose quad mesh is not a closed all-quad manifold is flagged in the report and warned about on stderr (-q).
TEST_F(OneTruthCli, RemeshSurfaceCheckMatchesInfoAndMetricsOfTheOutput) {
  write_sliver_ellipsoid(path("sliver.obj"));
  for (const std::string& in :
       {path("sliver.obj"), testing::data_path("couplingdown_genus9"), testing::data_path("lilium_disk")}) {
    const CliRun r = run("remesh " + in + " -o " + path("q.obj") + " --report " + path("q.json") + " -q");
    ASSERT_EQ(r.code, 0) << in << ": " << r.err;
    std::ifstream rin(path("q.json"));
    const nlohmann::json report = nlohmann::json::parse(rin);
    const nlohmann::json& out = report["surface_check"]["output"];
    const nlohmann::json info = json_of("info " + path("q.obj"));
    const nlohmann::json metrics = json_of("metrics " + path("q.obj"))["quad_mesh"];
    for (const char* key : kTopologyKeys) {
      EXPECT_EQ(out[key], info[key]) << in << " info " << key;
      EXPECT_EQ(out[key], metrics[key]) << in << " metrics " << key;
      EXPECT_EQ(out[key], report["quad_mesh"][key]) << in << " quad_mesh " << key;
    }
    EXPECT_EQ(out["non_quads"], metrics["non_quads"]) << in;
    const bool closed_input = report["surface_check"]["input"]["boundary_loops"].get<int>() == 0;
    const bool clean = out["closed"].get<bool>() && out["manifold"].get<bool>() && out["oriented"].get<bool>() &&
                       out["non_quads"].get<int>() == 0;
    if (closed_input) {
      EXPECT_EQ(report["surface_check"]["closed_all_quads"].get<bool>(), clean) << in;
    }
    if (closed_input && !clean) {
      EXPECT_NE(r.err.find("warning: " + in + ": remesh changed the surface"), std::string::npos) << in << r.err;
    }
    // Item 9: every warning of the report is on stderr with -q, and non-quads or repairs always give one.
    for (const auto& w : report["warnings"])
      EXPECT_NE(r.err.find(w.get<std::string>()), std::string::npos) << in << ": " << w;
    const nlohmann::json& e = report["extraction"];
    int repairs = 0;
    for (const char* key : {"unfolded_triangles", "moved_vertices", "collapsed_edges", "flipped_triangles",
                            "degenerate_triangles", "torn_seams", "failed_traces", "dropped_faces", "filled_holes"})
      repairs += e[key].get<int>();
    if (repairs > 0) {
      EXPECT_NE(r.err.find("the extraction repaired the map"), std::string::npos) << in << r.err;
    }
    if (out["non_quads"].get<int>() > 0) {
      EXPECT_NE(r.err.find("faces are not quads"), std::string::npos) << in << r.err;
    }
  }
}

// Item 9: `param` on the sliver either writes a seamless map or exits non-zero, naming the problem, with no file.
TEST_F(OneTruthCli, ParamIsSeamlessOrWritesNothing) {
  write_sliver_ellipsoid(path("sliver.obj"));
  const CliRun r = run("param " + path("sliver.obj") + " -o " + path("p.obj") + " -q");
  if (r.code == 0) {
    const PolygonSoup soup = read_mesh(path("p.obj"));
    const Mesh mesh = build_mesh(soup).mesh;
    Eigen::MatrixX3cd uv(mesh.num_faces(), 3);
    for (int f = 0; f < mesh.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) {
        const auto t = soup.face_uv[soup.face_offsets[f] + k];
        uv(f, k) = {soup.uv(t, 0), soup.uv(t, 1)};
      }
    EXPECT_TRUE(measure_seams(mesh, uv).seamless);
  } else {
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("not seamless"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nothing written"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("p.obj")));
  }
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

/// A parameterized OBJ of a 4×4 grid (32 triangles, planar UVs) in which triangle 5 is folded over (flipped) and
/// triangle 12 has a parameter area of −1e-12 of its share (negative, but within τ = 1e-8: collapsed).
void write_flipped_map(const std::string& file) {
  const Mesh grid = testing::make_grid(4);
  Eigen::MatrixX3cd uv(grid.num_faces(), 3);
  for (int f = 0; f < grid.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) uv(f, k) = {4 * grid.V()(grid.F()(f, k), 0), 4 * grid.V()(grid.F()(f, k), 1)};
  {
    const Complex a = uv(5, 1), b = uv(5, 2), c = uv(5, 0), d = (b - a) / std::abs(b - a);
    uv(5, 0) = a + d * std::conj((c - a) / d);  // mirrored through the opposite edge
  }
  {
    const Complex a = uv(12, 1), b = uv(12, 2), d = (b - a) / std::abs(b - a);
    uv(12, 0) = 0.5 * (a + b) - Complex(0, 1) * d * 1e-12;  // just to the right of a → b: a tiny negative area
  }
  std::ofstream out(file);
  out.precision(17);
  for (int v = 0; v < grid.num_vertices(); ++v)
    out << "v " << grid.V()(v, 0) << " " << grid.V()(v, 1) << " " << grid.V()(v, 2) << "\n";
  for (int f = 0; f < grid.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) out << "vt " << uv(f, k).real() << " " << uv(f, k).imag() << "\n";
  for (int f = 0; f < grid.num_faces(); ++f) {
    out << "f";
    for (int k = 0; k < 3; ++k) out << " " << grid.F()(f, k) + 1 << "/" << 3 * f + k + 1;
    out << "\n";
  }
}

// Item 8: one count of flips and cones. On a generated map (one fold, one triangle negative within the tolerance)
// and on the map `param` writes for bunny_3k, `render --uv-layout` counts (and draws) what `metrics` and the param
// report count, and `render` marks the report's cones.
TEST_F(OneTruthCli, RenderCountsFlipsAndConesAsTheReportsDo) {
  write_flipped_map(path("flip.obj"));
  const nlohmann::json layout = json_of("render " + path("flip.obj") + " --uv-layout -o " + path("flip.png"));
  const nlohmann::json metrics = json_of("metrics " + path("flip.obj") + " --no-extract")["parameterization"];
  EXPECT_EQ(layout["flipped_triangles"], 1);
  EXPECT_EQ(layout["collapsed_triangles"], 1);  // a sign test alone would call it a second flip
  EXPECT_EQ(metrics["flipped_triangles"], 1);
  json_of("metrics " + path("flip.obj") + " --no-extract --report " + path("fm.json"));
  std::ifstream fin(path("fm.json"));
  const nlohmann::json fm = nlohmann::json::parse(fin)["parameterization"];
  EXPECT_EQ(layout["collapsed_triangles"], fm["collapsed_triangles"]);
  EXPECT_EQ(layout["non_positive_triangles"], fm["non_positive_triangles"]);

  const std::string bunny = testing::data_path("bunny_3k");
  ASSERT_EQ(run("param " + bunny + " -o " + path("b.obj") + " --report " + path("b.json") + " -q").code, 0);
  std::ifstream bin(path("b.json"));
  const nlohmann::json p = nlohmann::json::parse(bin)["parameterization"];
  const nlohmann::json bl = json_of("render " + path("b.obj") + " --uv-layout -o " + path("b_uv.png"));
  const nlohmann::json bt = json_of("render " + path("b.obj") + " -o " + path("b.png"));
  const nlohmann::json bm = json_of("metrics " + path("b.obj") + " --no-extract")["parameterization"];
  for (const char* key : {"flipped_triangles", "collapsed_triangles", "non_positive_triangles"})
    EXPECT_EQ(bl[key], p[key]) << "render --uv-layout " << key;
  EXPECT_EQ(bt["cones"], p["branch_points"]);
  EXPECT_EQ(bm["branch_points"], p["branch_points"]);
  EXPECT_EQ(bm["flipped_triangles"], p["flipped_triangles"]);
}

// Item 16: unreferenced vertices in the middle of the file. `param` writes them back (same count, same positions,
// the faces over the same numbers) and says so; `remesh` (a new mesh) says how many it dropped.
TEST_F(OneTruthCli, UnreferencedVerticesKeepTheirNumbersOrAreCounted) {
  const Mesh e = testing::make_ellipsoid(2, 1.0, 0.8, 0.6);
  const int k = e.num_vertices() / 2;  // two unreferenced vertices inserted before vertex k
  {
    std::ofstream out(path("u.obj"));
    out.precision(17);
    for (int v = 0; v < e.num_vertices(); ++v) {
      if (v == k) out << "v 7 7 7\nv 8 8 8\n";
      out << "v " << e.V()(v, 0) << " " << e.V()(v, 1) << " " << e.V()(v, 2) << "\n";
    }
    for (int f = 0; f < e.num_faces(); ++f) {
      out << "f";
      for (int c = 0; c < 3; ++c) out << " " << e.F()(f, c) + 1 + (e.F()(f, c) >= k ? 2 : 0);
      out << "\n";
    }
  }
  const PolygonSoup in = read_mesh(path("u.obj"));
  const CliRun r = run("param " + path("u.obj") + " -o " + path("u.param.obj") + " --quads 300");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("2 unreferenced vertices"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the input's vertex numbers"), std::string::npos) << r.err;
  const PolygonSoup out = read_mesh(path("u.param.obj"));
  ASSERT_EQ(out.num_vertices(), in.num_vertices());
  EXPECT_EQ(out.positions, in.positions);
  ASSERT_EQ(out.num_faces(), in.num_faces());
  EXPECT_EQ(out.face_vertices, in.face_vertices);
  EXPECT_TRUE(out.has_uv());

  const CliRun q = run("remesh " + path("u.obj") + " -o " + path("u.quad.obj") + " --faces 300");
  ASSERT_EQ(q.code, 0) << q.err;
  EXPECT_NE(q.err.find("2 unreferenced vertices (used by no face) dropped"), std::string::npos) << q.err;
}

}  // namespace
}  // namespace quadcover
