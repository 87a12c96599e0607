// `quadcover param` end to end: the OBJ it writes is re-read here and checked independently (seamless transitions
// across every interior edge, vt in grid units), and the JSON report carries the required keys.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/read_mesh.h"
#include "mesh/mesh.h"
#include "param/seams.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

namespace fs = std::filesystem;

int run(const std::string& args) {
  const std::string cmd = std::string(QUADCOVER_CLI) + " " + args + " > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Reads the v/vt/f v/vt lines of an OBJ: per-face corner coordinates.
Eigen::MatrixX3cd read_corner_uv(const std::string& path, int faces) {
  std::ifstream in(path);
  std::vector<Complex> vt;
  Eigen::MatrixX3cd uv(faces, 3);
  std::string line;
  int f = 0;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "vt") {
      double x, y;
      s >> x >> y;
      vt.emplace_back(x, y);
    } else if (tag == "f") {
      for (int c = 0; c < 3; ++c) {
        std::string corner;
        s >> corner;
        uv(f, c) = vt.at(std::stoul(corner.substr(corner.find('/') + 1)) - 1);
      }
      ++f;
    }
  }
  EXPECT_EQ(f, faces);
  return uv;
}

TEST(ParamCli, WritesSeamlessObjAndReport) {
  ASSERT_TRUE(fs::exists(QUADCOVER_CLI)) << "build the quadcover target first";
  const fs::path dir = fs::temp_directory_path() / ("qc_param_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* name : {"bunny_3k", "lilium_disk"}) {
    const std::string obj = (dir / (std::string(name) + ".obj")).string();
    const std::string json = (dir / (std::string(name) + ".json")).string();
    ASSERT_EQ(run("param " + testing::data_path(name) + " -o " + obj + " --quads 400 --report " + json), 0) << name;
    // The map's triangulation as written (the input's, or its refinement for the curve constraints).
    const Mesh mesh = build_mesh(read_mesh(obj)).mesh;
    const Mesh input = testing::load_test_mesh(name);
    const Eigen::MatrixX3cd uv = read_corner_uv(obj, mesh.num_faces());
    const SeamReport seams = measure_seams(mesh, uv, 1e-9);
    EXPECT_TRUE(seams.seamless) << name << " " << seams.max_transition_error;
    EXPECT_GT(seams.cut_edges, 0);
    std::ifstream in(json);
    const nlohmann::json report = nlohmann::json::parse(in);
    for (const char* key : {"schema_version", "job", "mesh", "options", "field", "parameterization", "optimize",
                            "rounding", "relaxation", "stiffening", "aligned_curves", "warnings", "seconds"})
      EXPECT_TRUE(report.contains(key)) << key;
    const nlohmann::json& map = report["parameterization"];
    for (const char* key : {"branch_points", "h_sym", "energy_curl", "energy_harmonic", "flipped_triangles",
                            "flipped_faces", "seamless", "max_transition_error"})
      EXPECT_TRUE(map.contains(key)) << key;
    EXPECT_EQ(report["job"], "param");
    EXPECT_EQ(report["mesh"]["faces"], input.num_faces());
    EXPECT_EQ(report["refinement"]["faces"], mesh.num_faces());
    EXPECT_EQ(mesh.num_vertices(), input.num_vertices() + report["refinement"]["added_vertices"].get<int>());
    EXPECT_LT((mesh.V().topRows(input.num_vertices()) - input.V()).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_TRUE(map["seamless"].get<bool>());
    // Fields with branch points on these meshes: no degenerate-holonomy or half-integer warnings.
    ASSERT_TRUE(report["warnings"].is_array());
    // The refinement, the triangles left non-positive and an invalid map (pipeline/validity_retries.h) are said,
    // nothing else.
    int refined = 0, folded = 0, invalid = 0;
    for (const auto& w : report["warnings"]) {
      refined += w.get<std::string>().find("refined triangulation") != std::string::npos;
      folded += w.get<std::string>().find("stay flipped or collapsed") != std::string::npos;
      invalid += w.get<std::string>().find("not valid") != std::string::npos;
    }
    EXPECT_EQ(refined, report["refinement"]["split_edges"].get<int>() > 0 ? 1 : 0);
    EXPECT_EQ(folded, report["parameterization"]["non_positive_triangles"].get<int>() > 0 ? 1 : 0);
    const bool valid = map["non_positive_triangles"] == 0 && map["wrong_windings"] == 0;
    EXPECT_EQ(invalid, valid && report["validity_retries"]["used"] == 0 ? 0 : 1);
    EXPECT_EQ(static_cast<int>(report["warnings"].size()), refined + folded + invalid);
    EXPECT_EQ(map["non_positive_triangles"].get<int>(), static_cast<int>(map["flipped_faces"].size()));
    EXPECT_EQ(map["flipped_triangles"].get<int>(), flipped_triangles(mesh, uv).flipped);
    EXPECT_EQ(map["collapsed_triangles"].get<int>(), flipped_triangles(mesh, uv).collapsed);
    // --quads 400: about 400 unit squares of parameter area.
    EXPECT_NEAR(flipped_triangles(mesh, uv).parameter_area, 400, 200);
  }
  // Bad input and reserved options: exit status 2, no output file left behind.
  const std::string out = (dir / "bad.obj").string();
  EXPECT_EQ(run("param " + testing::data_path("bad/spot_duplicate_face.obj") + " -o " + out), 2);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(run("param " + testing::data_path("bunny_3k") + " -o " + out + " --rounding search"), 2);
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadcover
