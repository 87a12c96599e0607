// PLY outputs through the real binary: `remesh -o q.ply --ply-quality` writes binary PLY with per-vertex quality and
// valence (checked against a recomputation from the OBJ output of the same run), `param -o m.ply` writes the map's
// per-corner texcoord (equal to the OBJ's vt within float32 rounding); formats without texture coordinates are
// refused for param, --ply-quality without .ply too (exit 2, nothing written).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "io/read_mesh.h"
#include "metrics/vertex_quality.h"
#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace {

namespace fs = std::filesystem;
using quadcover::PolygonSoup;
using quadcover::testing::kWithoutRepairs;
using quadcover::testing::run_cli;
using quadcover::testing::slurp;

class PlyOutputCli : public quadcover::testing::FolderTest {
 protected:
  PlyOutputCli() : FolderTest("ply_output_cli") {}
};

/// A little-endian binary PLY body after the header: reads values in order.
struct Body {
  std::string data;
  std::size_t pos;
  template <class T>
  T get() {
    T v{};
    EXPECT_LE(pos + sizeof(T), data.size());
    if (pos + sizeof(T) <= data.size()) std::memcpy(&v, data.data() + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
};

Body body_after_header(const std::string& file, const std::string& expected_header) {
  EXPECT_EQ(file.compare(0, expected_header.size(), expected_header), 0) << file.substr(0, expected_header.size());
  return {file, expected_header.size()};
}

std::vector<std::vector<int>> polygons(const PolygonSoup& s) {
  std::vector<std::vector<int>> faces;
  for (std::size_t f = 0; f < s.num_faces(); ++f) faces.emplace_back(s.face_begin(f), s.face_begin(f) + s.face_size(f));
  return faces;
}

TEST_F(PlyOutputCli, RemeshQualityPlyMatchesTheObjOutput) {
  const std::string in = quadcover::testing::data_path("fandisk");
  ASSERT_EQ(run_cli("remesh " + in + " -o " + path("q.obj") + kWithoutRepairs + " -q").code, 0);
  ASSERT_EQ(run_cli("remesh " + in + " -o " + path("q.ply") + " --ply-quality" + kWithoutRepairs + " -q").code, 0);
  const PolygonSoup obj = quadcover::read_mesh(path("q.obj"));
  const PolygonSoup ply = quadcover::read_mesh(path("q.ply"));  // the project's reader skips the extra properties
  EXPECT_EQ(ply.positions, obj.positions);
  EXPECT_EQ(ply.face_vertices, obj.face_vertices);
  const std::string nv = std::to_string(obj.num_vertices()), nf = std::to_string(obj.num_faces());
  Body b = body_after_header(
      slurp(path("q.ply")), "ply\nformat binary_little_endian 1.0\ncomment written by quadcover\nelement vertex " + nv +
                                "\nproperty double x\nproperty double y\nproperty double z\nproperty float "
                                "quality\nproperty int valence\nelement face " +
                                nf + "\nproperty list uchar int vertex_indices\nend_header\n");
  const quadcover::VertexQuality q = quadcover::vertex_quality(obj.positions, polygons(obj));
  int valence4 = 0;
  for (Eigen::Index v = 0; v < obj.positions.rows(); ++v) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(b.get<double>(), obj.positions(v, c));
    EXPECT_EQ(b.get<float>(), static_cast<float>(q.worst_angle_deviation[v]));
    const int valence = b.get<std::int32_t>();
    EXPECT_EQ(valence, q.valence[v]);
    valence4 += valence == 4;
  }
  EXPECT_GT(valence4, obj.positions.rows() / 2);  // mostly regular
  for (std::size_t f = 0; f < obj.num_faces(); ++f) {
    ASSERT_EQ(b.get<std::uint8_t>(), obj.face_size(f));
    for (std::size_t k = 0; k < obj.face_size(f); ++k) EXPECT_EQ(b.get<std::int32_t>(), obj.face_begin(f)[k]);
  }
  EXPECT_EQ(b.pos, b.data.size());
  // Without the flag a .ply has no extra properties.
  ASSERT_EQ(run_cli("remesh " + in + " -o " + path("plain.ply") + kWithoutRepairs + " -q").code, 0);
  EXPECT_EQ(slurp(path("plain.ply")).find("quality"), std::string::npos);
}

TEST_F(PlyOutputCli, ParamPlyHasTheObjTexcoordsPerCorner) {
  const std::string in = quadcover::testing::data_path("camelhead_boundary");
  ASSERT_EQ(run_cli("param " + in + " -o " + path("m.obj") + kWithoutRepairs + " -q").code, 0);
  ASSERT_EQ(
      run_cli("param " + in + " -o " + path("m.ply") + kWithoutRepairs + " --report " + path("m.json") + " -q").code, 0);
  const PolygonSoup obj = quadcover::read_mesh(path("m.obj"));
  ASSERT_TRUE(obj.has_uv());
  const std::string nv = std::to_string(obj.num_vertices()), nf = std::to_string(obj.num_faces());
  Body b = body_after_header(
      slurp(path("m.ply")), "ply\nformat binary_little_endian 1.0\ncomment written by quadcover\nelement vertex " + nv +
                                "\nproperty double x\nproperty double y\nproperty double z\nelement face " + nf +
                                "\nproperty list uchar int vertex_indices\nproperty list uchar float "
                                "texcoord\nend_header\n");
  for (Eigen::Index v = 0; v < obj.positions.rows(); ++v)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(b.get<double>(), obj.positions(v, c));
  double worst = 0;
  for (std::size_t f = 0; f < obj.num_faces(); ++f) {
    ASSERT_EQ(b.get<std::uint8_t>(), 3);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(b.get<std::int32_t>(), obj.face_begin(f)[k]);
    ASSERT_EQ(b.get<std::uint8_t>(), 6);
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 2; ++c) {
        const double vt = obj.uv(obj.face_uv[obj.face_offsets[f] + k], c);
        const float t = b.get<float>();
        EXPECT_EQ(t, static_cast<float>(vt));
        worst = std::max(worst, std::abs(t - vt));
      }
  }
  EXPECT_EQ(b.pos, b.data.size());
  const auto report = nlohmann::json::parse(slurp(path("m.json")));
  EXPECT_NEAR(report["texcoord_float32_rounding"].get<double>(), worst, 1e-12);
  EXPECT_LT(worst, 1e-4);
}

TEST_F(PlyOutputCli, FormatsWithoutTexcoordsAndMisplacedFlagsAreRefused) {
  const std::string in = quadcover::testing::data_path("fandisk");
  for (const std::string& args : {"param " + in + " -o " + path("m.off"), "param " + in + " -o " + path("m.stl"),
                                  "remesh " + in + " -o " + path("q.obj") + " --ply-quality"}) {
    SCOPED_TRACE(args);
    const auto r = run_cli(args + " -q", path("err.txt"));
    EXPECT_EQ(r.code, 2);
    EXPECT_FALSE(r.err.empty());
  }
  EXPECT_TRUE(fs::is_empty(dir) || (fs::exists(path("err.txt")) &&
                                    std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1));
}

}  // namespace
