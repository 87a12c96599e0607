// PLY reader: real meshes converted to ASCII and binary (both byte orders) and reread exactly; hand-made files
// with other numeric types, extra properties and elements; malformed headers and truncated data.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>

#include "io/read_mesh.h"
#include "io/write_ply.h"
#include "io_test_util.h"
#include "mesh/mesh.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

using testing::expect_input_error;

struct PlyCase {
  const char* mesh;
  PlyEncoding encoding;
};

class PlyOnRealMeshes : public ::testing::TestWithParam<PlyCase> {};

TEST_P(PlyOnRealMeshes, ConvertedMeshRereadsExactly) {
  testing::TempDir dir;
  const PolygonSoup obj = read_obj(testing::data_path(GetParam().mesh));
  write_ply(dir.file("m.ply"), obj, GetParam().encoding);
  const PolygonSoup ply = read_mesh(dir.file("m.ply"));
  EXPECT_EQ(ply.positions, obj.positions);
  EXPECT_EQ(ply.face_vertices, obj.face_vertices);
  EXPECT_EQ(ply.face_offsets, obj.face_offsets);
  ASSERT_EQ(ply.face_lines.size(), ply.num_faces());
  if (GetParam().encoding == PlyEncoding::Ascii) {
    EXPECT_EQ(ply.location_unit, "line");
    EXPECT_EQ(ply.vertex_lines.front(), 11);  // the header has 10 lines
  } else {
    EXPECT_EQ(ply.location_unit, "element");
    EXPECT_EQ(ply.face_lines.back(), static_cast<long>(ply.num_faces()));
  }
  ValidationOptions triangulate;
  triangulate.triangulate = true;  // the quad mesh case
  EXPECT_EQ(build_mesh(ply, triangulate).mesh.genus(), build_mesh(obj, triangulate).mesh.genus());
}

INSTANTIATE_TEST_SUITE_P(Meshes, PlyOnRealMeshes,
                         ::testing::Values(PlyCase{"torus_5k", PlyEncoding::Ascii},
                                           PlyCase{"torus_5k", PlyEncoding::BinaryLittleEndian},
                                           PlyCase{"torus_5k", PlyEncoding::BinaryBigEndian},
                                           PlyCase{"mech_holes_shark", PlyEncoding::BinaryBigEndian},
                                           PlyCase{"bad/spot_quads_nontriangle", PlyEncoding::BinaryLittleEndian}));

// Binary body builder for hand-made files.
class Bytes {
 public:
  explicit Bytes(bool big) : big_(big) {}
  template <class T>
  Bytes& put(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big_ != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
    s_.append(reinterpret_cast<const char*>(b), sizeof(T));
    return *this;
  }
  const std::string& str() const { return s_; }

 private:
  bool big_;
  std::string s_;
};

TEST(ReadPly, AsciiWithExtraPropertiesAndElements) {
  const std::string text =
      "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info none\r\n"
      "element vertex 4\r\nproperty float nx\r\nproperty int x\r\nproperty uchar red\r\nproperty double y\r\n"
      "property short z\r\nproperty list uchar float extra\r\n"
      "element face 2\r\nproperty uchar flags\r\nproperty list ushort uint vertex_index\r\n"
      "property list uchar float texcoord\r\n"
      "element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\n"
      "end_header\r\n"
      "0.5 0 255 0 0 0\r\n"
      "0.5 1 255 0 0 2 1.5 2.5\r\n"
      "0.5 1 255 1.25 0 0\r\n"
      "0.5 0 255 1 -3 1 7\r\n"
      "1 3 0 1 2 6 0 0 1 0 1 1\r\n"
      "\r\n"  // blank lines between elements are tolerated
      "0 4 0 2 3 1 0\r\n"
      "0 1\r\n";
  const PolygonSoup s = read_ply_from_memory(text, "h.ply");
  ASSERT_EQ(s.num_vertices(), 4u);
  ASSERT_EQ(s.num_faces(), 2u);
  EXPECT_EQ(s.positions(2, 0), 1.0);
  EXPECT_EQ(s.positions(2, 1), 1.25);
  EXPECT_EQ(s.positions(3, 2), -3.0);
  EXPECT_EQ(s.face_size(1), 4u);
  EXPECT_EQ(s.face_vertices, (std::vector<std::int64_t>{0, 1, 2, 0, 2, 3, 1}));
  EXPECT_EQ(s.vertex_lines, (std::vector<long>{20, 21, 22, 23}));
  EXPECT_EQ(s.face_lines, (std::vector<long>{24, 26}));
}

TEST(ReadPly, BinaryBigEndianWithMixedTypes) {
  std::string text =
      "ply\nformat binary_big_endian 1.0\n"
      "element material 2\nproperty uchar r\nproperty double shininess\n"  // a fixed-size element, skipped whole
      "element vertex 3\nproperty short x\nproperty float y\nproperty uint8 alpha\nproperty double z\n"
      "element face 1\nproperty list uint int16 vertex_indices\nproperty list uchar int8 extra\n"
      "end_header\n";
  Bytes b(/*big=*/true);
  b.put<std::uint8_t>(1).put(2.0).put<std::uint8_t>(3).put(4.0);
  b.put<std::int16_t>(-7).put(0.5f).put<std::uint8_t>(9).put(1e-300);
  b.put<std::int16_t>(300).put(-1.5f).put<std::uint8_t>(9).put(2.0);
  b.put<std::int16_t>(0).put(0.0f).put<std::uint8_t>(9).put(3.0);
  b.put<std::uint32_t>(3).put<std::int16_t>(2).put<std::int16_t>(0).put<std::int16_t>(1);
  b.put<std::uint8_t>(2).put<std::int8_t>(-1).put<std::int8_t>(-2);
  text += b.str();
  const PolygonSoup s = read_ply_from_memory(text, "be.ply");
  ASSERT_EQ(s.num_vertices(), 3u);
  EXPECT_EQ(s.positions(0, 0), -7.0);
  EXPECT_EQ(s.positions(0, 1), 0.5);
  EXPECT_EQ(s.positions(0, 2), 1e-300);
  EXPECT_EQ(s.positions(1, 0), 300.0);
  EXPECT_EQ(s.positions(1, 1), -1.5);
  EXPECT_EQ(s.face_vertices, (std::vector<std::int64_t>{2, 0, 1}));
  EXPECT_EQ(s.face_lines, (std::vector<long>{1}));
  EXPECT_EQ(s.face_location(0), "be.ply, face element 1");
}

std::string binary_header(const std::string& vertex_count, const std::string& face_count) {
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + vertex_count +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + face_count +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string three_vertices() {
  Bytes b(false);
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) b.put(v);
  return b.str();
}

TEST(ReadPly, HeaderCountsAreCheckedAgainstTheFileSize) {
  // 2^40 vertices declared, 36 bytes present: rejected before any allocation.
  const InputError e = expect_input_error(
      [] { read_ply_from_memory(binary_header("1099511627776", "0") + three_vertices(), "huge.ply"); });
  EXPECT_EQ(e.line(), 3);  // the element line
  EXPECT_NE(std::string(e.what()).find("declares 1099511627776 vertex elements"), std::string::npos) << e.what();

  // Face list longer than the data.
  Bytes f(false);
  f.put<std::uint8_t>(250).put<std::int32_t>(0).put<std::int32_t>(1).put<std::int32_t>(2);
  const InputError g = expect_input_error(
      [&] { read_ply_from_memory(binary_header("3", "1") + three_vertices() + f.str(), "long.ply"); });
  EXPECT_NE(std::string(g.what()).find("face element 1: list of 250 items runs past the end"), std::string::npos)
      << g.what();

  // Truncated in the middle of the second face.
  Bytes t(false);
  t.put<std::uint8_t>(3).put<std::int32_t>(0).put<std::int32_t>(1).put<std::int32_t>(2).put<std::uint8_t>(3).put<std::int32_t>(0);
  const InputError h = expect_input_error(
      [&] { read_ply_from_memory(binary_header("3", "2") + three_vertices() + t.str(), "trunc.ply"); });
  EXPECT_NE(std::string(h.what()).find("face element 2"), std::string::npos) << h.what();
  EXPECT_NE(std::string(h.what()).find("trunc.ply"), std::string::npos) << h.what();
}

struct BadPly {
  const char* text;
  long line;
  const char* fragment;
};

class MalformedPly : public ::testing::TestWithParam<BadPly> {};

TEST_P(MalformedPly, ThrowsWithLine) {
  const BadPly bad = GetParam();
  const InputError e = expect_input_error([&] { read_ply_from_memory(bad.text, "bad.ply"); });
  EXPECT_EQ(e.line(), bad.line) << e.what();
  EXPECT_NE(std::string(e.what()).find(bad.fragment), std::string::npos) << e.what();
}

#define PLY_ASCII_HEAD "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedPly,
    ::testing::Values(
        BadPly{"plyx\n", 1, "not a PLY file"}, BadPly{"ply\nformat ascii 1.0\nelement vertex 1\n", 3, "no 'end_header'"},
        BadPly{"ply\nformat ascii 2.0 x\nformat cobol 1.0\n", 3, "unknown PLY format 'cobol'"},
        BadPly{"ply\nend_header\n", 2, "no 'format'"},
        BadPly{"ply\nformat ascii 1.0\nproperty float x\nend_header\n", 3, "before any element"},
        BadPly{"ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", 3, "COUNT >= 0"},
        BadPly{"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n", 4, "unknown PLY property type 'quad'"},
        BadPly{"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n", 4, "integer type"},
        BadPly{"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n", 3,
               "lacks one of the properties x, y, z"},
        BadPly{PLY_ASCII_HEAD "element face 1\nproperty list uchar int corners\nend_header\n", 7, "no list property"},
        BadPly{PLY_ASCII_HEAD "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1\n",
               12, "property 'z' is missing"},
        BadPly{PLY_ASCII_HEAD "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n", 12,
               "file ends after 0 of 1 face elements"},
        BadPly{PLY_ASCII_HEAD "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                              "3 0 1\n",
               13, "declares 3 items but item 2 is missing"},
        BadPly{PLY_ASCII_HEAD "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                              "3 0 1 2 5\n",
               13, "more values than the header declares"},
        BadPly{PLY_ASCII_HEAD "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                              "2 0 1\n",
               13, "2 corners"},
        BadPly{"ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n", 0,
               "exactly one 'vertex' element"}));

}  // namespace
}  // namespace quadcover
