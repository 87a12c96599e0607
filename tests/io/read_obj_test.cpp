// OBJ reader: positions, polygon corners in all four syntaxes, negative indices, per-corner texture
// coordinates, and malformed lines reported with their line numbers.
#include <gtest/gtest.h>

#include "io/read_mesh.h"
#include "io_test_util.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

using testing::expect_input_error;

TEST(ReadObj, CornerSyntaxesAndRelativeIndices) {
  const std::string text =
      "# a comment\n"
      "v 0 0 0\n"
      "v 1 0 0 1.0\n"        // optional w
      "v 1 1 0 0.5 0.5 0.5\n"  // vertex colour
      "v 0 1 0\n"
      "vn 0 0 1\n"
      "f 1 2 3\n"
      "f 1/1 3/2 4/3\n"
      "f 1//1 3//1 4//1\n"
      "f -4/1/1 -3/2/1 -2/3/1 -1/1/1\n"
      "vt 0 0\nvt 1 0\nvt 1 1\n";
  // The face with v/vt corners comes before the vt lines: that is an error (indices refer to earlier lines).
  const InputError e = expect_input_error([&] { read_obj_from_memory(text, "t.obj"); });
  EXPECT_EQ(e.line(), 8);
  EXPECT_NE(std::string(e.what()).find("t.obj:8"), std::string::npos) << e.what();

  const std::string good =
      "v 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\nvn 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\n"
      "f 1 2 3\n"
      "f 1/1 3/2 4/3\n"
      "f 1//1 3//1 4//1\n"
      "f -4/1/1 -3/2/1 -2/3/1 -1/1/1\n";
  const PolygonSoup soup = read_obj_from_memory(good, "t.obj");
  ASSERT_EQ(soup.num_vertices(), 4u);
  ASSERT_EQ(soup.num_faces(), 4u);
  EXPECT_EQ(soup.positions(2, 1), 1.0);
  EXPECT_EQ(soup.face_size(3), 4u);
  const std::vector<std::int64_t> expect_v = {0, 1, 2, 0, 2, 3, 0, 2, 3, 0, 1, 2, 3};
  EXPECT_EQ(soup.face_vertices, expect_v);
  EXPECT_EQ(soup.face_lines, (std::vector<long>{9, 10, 11, 12}));
  EXPECT_EQ(soup.vertex_lines, (std::vector<long>{1, 2, 3, 4}));
  ASSERT_TRUE(soup.has_uv());
  ASSERT_EQ(soup.uv.rows(), 3);
  EXPECT_EQ(soup.uv(2, 0), 1.0);
  // -1 where a corner has no vt; relative vt indices resolve against the vt lines read so far.
  const std::vector<std::int64_t> expect_t = {-1, -1, -1, 0, 1, 2, -1, -1, -1, 0, 1, 2, 0};
  EXPECT_EQ(soup.face_uv, expect_t);
}

TEST(ReadObj, NoTextureReferencesMeansNoUv) {
  const PolygonSoup soup = read_obj_from_memory("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nf 1 2 3\n", "t.obj");
  EXPECT_FALSE(soup.has_uv());
  EXPECT_EQ(soup.uv.rows(), 0);
}

TEST(ReadObj, TriangulationKeepsTextureCorners) {
  const PolygonSoup soup = read_obj_from_memory(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n", "q.obj");
  const PolygonSoup tri = triangulate_polygons(soup);
  ASSERT_EQ(tri.num_faces(), 2u);
  EXPECT_EQ(tri.face_uv, (std::vector<std::int64_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(tri.face_lines, (std::vector<long>{9, 9}));
}

TEST(ReadObj, RealMeshCounts) {
  const PolygonSoup soup = read_obj(testing::data_path("bunny_3k"));
  EXPECT_EQ(soup.num_vertices(), 1839u);
  EXPECT_EQ(soup.num_faces(), 3674u);
  EXPECT_EQ(soup.vertex_lines.size(), soup.num_vertices());
  EXPECT_EQ(soup.face_lines.size(), soup.num_faces());
}

struct BadObj {
  const char* text;
  long line;
  const char* fragment;
};

class MalformedObj : public ::testing::TestWithParam<BadObj> {};

TEST_P(MalformedObj, ThrowsWithLine) {
  const BadObj bad = GetParam();
  const InputError e = expect_input_error([&] { read_obj_from_memory(bad.text, "bad.obj"); });
  EXPECT_EQ(e.line(), bad.line) << e.what();
  EXPECT_EQ(e.file(), "bad.obj");
  EXPECT_NE(std::string(e.what()).find(bad.fragment), std::string::npos) << e.what();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedObj,
    ::testing::Values(BadObj{"v 0 0 0\nv 1 x 0\n", 2, "three numeric"}, BadObj{"v 0 0\n", 1, "three numeric"},
                      BadObj{"v 0 0 0\nv 1 0 0\nv 0 1 0\n\n\nf 1 2\n", 6, "2 corners"},
                      BadObj{"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 0 2\n", 4, "non-zero vertex index"},
                      BadObj{"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 a 2\n", 4, "bad face corner 'a'"},
                      BadObj{"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", 5, "texture coordinate 2"},
                      BadObj{"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 q\n", 4, "not a number"},
                      BadObj{"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n", 4, "bad face corner"}));

TEST(ReadObj, OutOfRangeVertexIndexIsLeftToValidation) {
  // A positive index may point ahead (vertices may follow): the reader keeps it, validation reports it with its line.
  const PolygonSoup soup = read_obj_from_memory("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "r.obj");
  EXPECT_EQ(soup.face_vertices[2], 6);
  // A negative one counts back from its line: reaching before the first vertex is an error here, quoted as written.
  const InputError e =
      expect_input_error([] { read_obj_from_memory("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -9 1 2\n", "r.obj"); });
  EXPECT_NE(std::string(e.what()).find("r.obj:4: face corner '-9' refers to vertex -9"), std::string::npos) << e.what();
}

TEST(ReadObj, TextWithoutAnyVertexOrFaceIsNotAnObjMesh) {
  const InputError e =
      expect_input_error([] { read_obj_from_memory("# comment\n\x01\x02garbage 1 2\nmore\n", "g.obj"); });
  EXPECT_NE(std::string(e.what()).find("g.obj:2: not an OBJ mesh file"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("\\x01\\x02garbage"), std::string::npos) << e.what();
  // A file with nothing but comments and blank lines stays an empty mesh (validation says so).
  EXPECT_EQ(read_obj_from_memory("# nothing\n\n", "e.obj").num_faces(), 0u);
}

TEST(ReadMesh, DispatchByExtension) {
  const InputError e = expect_input_error([] { read_mesh("/nonexistent/file.xyz"); });
  EXPECT_NE(std::string(e.what()).find("unsupported mesh format '.xyz'"), std::string::npos);
  const InputError missing = expect_input_error([] { read_mesh("/nonexistent/file.OBJ"); });
  EXPECT_NE(std::string(missing.what()).find("cannot open"), std::string::npos);
  EXPECT_EQ(file_extension("a/b.c/MESH.Ply"), "ply");
  EXPECT_EQ(file_extension("a/b.c/mesh"), "");
}

}  // namespace
}  // namespace quadcover
