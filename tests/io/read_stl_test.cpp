// STL reader: real meshes written as binary and ASCII STL and reread; welding must restore the shared vertices
// (same vertex count and topology as the original), deterministically in order of first appearance.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>

#include "io/read_mesh.h"
#include "io/write_stl.h"
#include "io_test_util.h"
#include "mesh/mesh.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

using testing::expect_input_error;

struct StlCase {
  const char* mesh;
  bool binary;
};

class StlOnRealMeshes : public ::testing::TestWithParam<StlCase> {};

TEST_P(StlOnRealMeshes, WeldingRestoresTheMesh) {
  testing::TempDir dir;
  const Mesh original = testing::load_test_mesh(GetParam().mesh);
  write_stl(dir.file("m.stl"), original.V(), original.F(), GetParam().binary);
  const PolygonSoup stl = read_mesh(dir.file("m.stl"));
  ASSERT_EQ(stl.num_vertices(), static_cast<std::size_t>(original.num_vertices()));
  ASSERT_EQ(stl.num_faces(), static_cast<std::size_t>(original.num_faces()));
  // Every corner has the original position (float32 precision in binary STL, exact in ASCII).
  const double tol = GetParam().binary ? 1e-6 * original.bounding_box_diagonal() : 0.0;
  for (int f = 0; f < original.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto v = stl.face_begin(static_cast<std::size_t>(f))[k];
      ASSERT_LE((stl.positions.row(v) - original.V().row(original.F()(f, k))).norm(), tol);
    }
  // Vertices are numbered in order of first appearance: corner i introduces vertex ids 0, 1, 2, ... in order.
  std::int64_t next = 0;
  for (std::int64_t v : stl.face_vertices) {
    ASSERT_LE(v, next);
    if (v == next) ++next;
  }
  const Mesh welded = build_mesh(stl).mesh;
  EXPECT_EQ(welded.genus(), original.genus());
  EXPECT_EQ(welded.num_boundary_loops(), original.num_boundary_loops());
  EXPECT_EQ(welded.num_edges(), original.num_edges());
}

INSTANTIATE_TEST_SUITE_P(Meshes, StlOnRealMeshes,
                         ::testing::Values(StlCase{"fertility_genus4", true}, StlCase{"camelhead_boundary", true},
                                           StlCase{"eight_genus2", false}, StlCase{"bunny_20k_holes", true}));

TEST(ReadStl, AsciiWeldsIdenticalPositionsIncludingSignedZero) {
  const std::string text =
      "solid two\n"
      "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 1 1 0\n"
      "    endloop\n  endfacet\n"
      "  facet normal 0 0 1\n    outer loop\n      vertex -0 0 0\n      vertex 1 1 0\n      vertex 0 1 -0.0\n"
      "    endloop\n  endfacet\n"
      "endsolid two\n";
  const PolygonSoup s = read_stl_from_memory(text, "two.stl");
  ASSERT_EQ(s.num_vertices(), 4u);
  EXPECT_EQ(s.face_vertices, (std::vector<std::int64_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(s.face_lines, (std::vector<long>{2, 9}));
  EXPECT_EQ(s.vertex_lines, (std::vector<long>{4, 5, 6, 13}));  // line of each vertex's first appearance
  // Reading twice gives the same result (no hash-order dependence).
  EXPECT_EQ(read_stl_from_memory(text, "two.stl").face_vertices, s.face_vertices);
}

std::string binary_stl(const std::string& header80, std::uint32_t declared, int actual) {
  std::string s = header80;
  s.resize(80, ' ');
  const std::uint32_t n = declared;
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>((n >> (8 * i)) & 0xff));
  for (int t = 0; t < actual; ++t) {
    const float rec[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, float(t), 1, 0};
    char b[48];
    std::memcpy(b, rec, 48);  // test machine is little endian (checked below)
    s.append(b, 48);
    s.append(2, '\0');
  }
  return s;
}

TEST(ReadStl, BinaryStartingWithSolidIsDetectedBySize) {
  static_assert(std::endian::native == std::endian::little);
  const PolygonSoup s = read_stl_from_memory(binary_stl("solid but binary", 3, 3), "b.stl");
  EXPECT_EQ(s.num_faces(), 3u);
  EXPECT_EQ(s.num_vertices(), 5u);  // (0,0,0) and (1,0,0) shared by all three facets
  EXPECT_EQ(s.location_unit, "element");
  EXPECT_EQ(s.vertex_location(4), "b.stl, facet element 3");
}

TEST(ReadStl, TruncatedBinaryIsRejectedWithCounts) {
  const InputError e = expect_input_error([] { read_stl_from_memory(binary_stl("binary", 1000, 2), "t.stl"); });
  EXPECT_NE(std::string(e.what()).find("declares 1000 triangles"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("184 bytes"), std::string::npos) << e.what();
  const InputError shorter = expect_input_error([] { read_stl_from_memory("not an stl", "s.stl"); });
  EXPECT_NE(std::string(shorter.what()).find("shorter than its 84-byte header"), std::string::npos);
}

struct BadStl {
  const char* text;
  long line;
  const char* fragment;
};

class MalformedStl : public ::testing::TestWithParam<BadStl> {};

TEST_P(MalformedStl, ThrowsWithLine) {
  const BadStl bad = GetParam();
  const InputError e = expect_input_error([&] { read_stl_from_memory(bad.text, "bad.stl"); });
  EXPECT_EQ(e.line(), bad.line) << e.what();
  EXPECT_NE(std::string(e.what()).find(bad.fragment), std::string::npos) << e.what();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedStl,
    ::testing::Values(
        BadStl{"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 one 0\n", 6, "three numeric"},
        BadStl{"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n", 6, "2 vertices"},
        BadStl{"solid x\nfacet normal 0 0 1\nloop\n", 3, "'outer loop'"},
        BadStl{"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendsolid\n", 8,
               "'endfacet'"},
        BadStl{"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n", 6,
               "ends inside the facet that starts on line 2"},
        BadStl{"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertx 1 0 0\n", 5, "expected 'vertex x y z'"},
        BadStl{"solid x\nendsolid x\nfacet\n", 3, "must start with 'solid'"},
        BadStl{"solid x\nvertex 0 0 0\n", 2, "expected 'facet' or 'endsolid'"}));

TEST(ReadStl, AsciiWithoutEndsolidAndSeveralSolids) {
  const std::string one = "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  EXPECT_EQ(read_stl_from_memory(one, "a.stl").num_faces(), 1u);
  const PolygonSoup two = read_stl_from_memory(one + "endsolid a\n" + one + "endsolid a\n", "b.stl");
  EXPECT_EQ(two.num_faces(), 2u);
  EXPECT_EQ(two.num_vertices(), 3u);
}

}  // namespace
}  // namespace quadcover
