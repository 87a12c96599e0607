// OFF reader: real meshes converted and reread, header variants, extras after coordinates and indices, and
// malformed files reported with their line numbers.
#include <gtest/gtest.h>

#include "io/read_mesh.h"
#include "io/write_off.h"
#include "io_test_util.h"
#include "mesh/mesh.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

using testing::expect_input_error;

class OffOnRealMeshes : public ::testing::TestWithParam<const char*> {};

TEST_P(OffOnRealMeshes, ConvertedMeshRereadsExactly) {
  testing::TempDir dir;
  const PolygonSoup obj = read_obj(testing::data_path(GetParam()));
  write_off(dir.file("m.off"), obj);
  const PolygonSoup off = read_mesh(dir.file("m.off"));
  EXPECT_EQ(off.positions, obj.positions);
  EXPECT_EQ(off.face_vertices, obj.face_vertices);
  EXPECT_EQ(off.face_offsets, obj.face_offsets);
  // Locations: header, counts, then one line per vertex and per face.
  EXPECT_EQ(off.vertex_lines.front(), 3);
  EXPECT_EQ(off.face_lines.back(), static_cast<long>(2 + obj.num_vertices() + obj.num_faces()));
  const Mesh a = build_mesh(obj).mesh, b = build_mesh(off).mesh;
  EXPECT_EQ(a.genus(), b.genus());
  EXPECT_EQ(a.num_boundary_loops(), b.num_boundary_loops());
}

INSTANTIATE_TEST_SUITE_P(Meshes, OffOnRealMeshes, ::testing::Values("bunny_3k", "eight_genus2", "lilium_disk"));

TEST(ReadOff, QuadMeshKeepsPolygons) {
  testing::TempDir dir;
  const PolygonSoup quads = read_obj(testing::data_path("bad/spot_quads_nontriangle.obj"));
  write_off(dir.file("q.off"), quads);
  const PolygonSoup off = read_off(dir.file("q.off"));
  EXPECT_EQ(off.face_offsets, quads.face_offsets);
  EXPECT_EQ(off.face_size(0), 4u);
}

TEST(ReadOff, HeaderVariantsCommentsAndExtras) {
  // COFF: colours after each vertex; counts on the header line; a face colour after the indices; comments.
  const std::string coff =
      "COFF 4 2 0 # counts on the header line\n"
      "# a comment line\n"
      "\n"
      "0 0 0 255 0 0 255\n"
      "1 0 0 0 255 0 255\n"
      "1 1 0 0 0 255 255\n"
      "0 1 0 9 9 9 255\n"
      "3 0 1 2 1.0 0.0 0.0\n"
      "3 0 2 3   # comment after a face\n";
  const PolygonSoup s = read_off_from_memory(coff, "c.off");
  ASSERT_EQ(s.num_vertices(), 4u);
  ASSERT_EQ(s.num_faces(), 2u);
  EXPECT_EQ(s.positions(2, 0), 1.0);
  EXPECT_EQ(s.positions(3, 1), 1.0);
  EXPECT_EQ(s.face_vertices, (std::vector<std::int64_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(s.vertex_lines, (std::vector<long>{4, 5, 6, 7}));
  EXPECT_EQ(s.face_lines, (std::vector<long>{8, 9}));

  // NOFF (normals after positions) with CRLF line ends; STOFF; and no header at all.
  const PolygonSoup n = read_off_from_memory("NOFF\r\n3 1 3\r\n0 0 0 0 0 1\r\n1 0 0 0 0 1\r\n0 1 0 0 0 1\r\n3 0 1 2\r\n", "n.off");
  EXPECT_EQ(n.num_faces(), 1u);
  EXPECT_EQ(n.positions(1, 0), 1.0);
  const PolygonSoup st = read_off_from_memory("STCNOFF\n3 1 0\n0 0 0 0 0 1 1 1 1 1 0 0\n1 0 0 0 0 1 1 1 1 1 1 0\n0 1 0 0 0 1 1 1 1 1 0 1\n3 0 1 2\n", "st.off");
  EXPECT_EQ(st.num_vertices(), 3u);
  const PolygonSoup bare = read_off_from_memory("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 2 1 0\n", "b.off");
  EXPECT_EQ(bare.face_vertices, (std::vector<std::int64_t>{2, 1, 0}));
  // Zero faces is readable (validation then reports an empty mesh).
  EXPECT_EQ(read_off_from_memory("OFF\n1 0 0\n0 0 0\n", "z.off").num_faces(), 0u);
}

struct BadOff {
  const char* text;
  long line;
  const char* fragment;
};

class MalformedOff : public ::testing::TestWithParam<BadOff> {};

TEST_P(MalformedOff, ThrowsWithLine) {
  const BadOff bad = GetParam();
  const InputError e = expect_input_error([&] { read_off_from_memory(bad.text, "bad.off"); });
  EXPECT_EQ(e.line(), bad.line) << e.what();
  EXPECT_NE(std::string(e.what()).find(bad.fragment), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("bad.off"), std::string::npos) << e.what();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedOff,
    ::testing::Values(BadOff{"", 0, "empty OFF"}, BadOff{"OFF\n", 1, "ends before"},
                      BadOff{"OFF\nthree 1 0\n", 2, "expected the counts"}, BadOff{"OFF\n3 -1 0\n", 2, "negative"},
                      // Huge counts are not trusted: the file simply ends early (no allocation from the header).
                      BadOff{"OFF\n999999999999 1 0\n0 0 0\n", 3, "file ends after 1 of 999999999999 vertices"},
                      BadOff{"OFF\n3 5 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 6, "file ends after 1 of 5 faces"},
                      BadOff{"OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", 4, "vertex 1 needs three"},
                      BadOff{"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 6, "2 corners"},
                      BadOff{"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", 6, "corner 4 is missing"},
                      BadOff{"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 x 2\n", 6, "corner 2"},
                      BadOff{"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\nthree 0 1 2\n", 6, "corner count"},
                      BadOff{"4OFF\n3 1 0\n", 1, "not supported"}, BadOff{"OFF BINARY\n", 1, "binary OFF"}));

}  // namespace
}  // namespace quadcover
