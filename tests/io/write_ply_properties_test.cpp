// PLY writer extras: per-vertex scalars (float / int) and per-corner texcoord lists, checked byte by byte against
// an independent parse of the exact header and body, in all three encodings; the project's reader still reads the
// positions and faces; bad properties leave no file.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <sstream>

#include "io/read_mesh.h"
#include "io/write_ply.h"
#include "io_test_util.h"
#include "support/cli_runner.h"

namespace quadcover {
namespace {

/// Two quads and a triangle sharing edges, with per-vertex quality/valence and per-corner uv (the triangle's last
/// corner has none).
PolygonSoup sample_soup() {
  Eigen::MatrixX3d V(6, 3);
  V << 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0.5, 2, 1, 0.25;
  const std::vector<std::vector<int>> faces{{0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 5}};
  PolygonSoup soup = PolygonSoup::from_polygons(V, faces);
  soup.uv.resize(4, 2);
  soup.uv << 0.1, 0.2, 1.5, -2.25, 1e-3, 3.0, 0.3333333333, 7.0;
  soup.face_uv = {0, 1, 2, 3, 1, 0, 3, 2, 0, 1, -1};
  return soup;
}

std::vector<PlyVertexProperty> sample_properties() {
  Eigen::VectorXd quality(6), valence(6);
  quality << 0.5, 12.25, 90, 1.0 / 3.0, 0, 45;
  valence << 2, 3, 2, 3, 4, 3;
  return {{"quality", quality, false}, {"valence", valence, true}};
}

const char* kHeader =
    "ply\nformat binary_little_endian 1.0\ncomment written by quadcover\nelement vertex 6\n"
    "property double x\nproperty double y\nproperty double z\nproperty float quality\nproperty int valence\n"
    "element face 3\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n";

/// Reads values of the file's byte order from `data` at `pos`.
struct Reader {
  const std::string& data;
  std::size_t pos;
  bool big;
  template <class T>
  T get() {
    EXPECT_LE(pos + sizeof(T), data.size());
    unsigned char b[sizeof(T)];
    std::memcpy(b, data.data() + pos, sizeof(T));
    if (big != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
    pos += sizeof(T);
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }
};

void expect_body(const std::string& file, std::size_t header_size, bool big) {
  const PolygonSoup soup = sample_soup();
  const auto props = sample_properties();
  Reader r{file, header_size, big};
  for (int v = 0; v < 6; ++v) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(r.get<double>(), soup.positions(v, c));
    EXPECT_EQ(r.get<float>(), static_cast<float>(props[0].values[v]));
    EXPECT_EQ(r.get<std::int32_t>(), static_cast<std::int32_t>(props[1].values[v]));
  }
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const std::size_t n = soup.face_size(f);
    ASSERT_EQ(r.get<std::uint8_t>(), n);
    for (std::size_t k = 0; k < n; ++k) EXPECT_EQ(r.get<std::int32_t>(), soup.face_begin(f)[k]);
    const std::uint8_t m = r.get<std::uint8_t>();
    if (f == 2) {  // a corner without uv: empty list
      EXPECT_EQ(m, 0);
      continue;
    }
    ASSERT_EQ(m, 2 * n);
    for (std::size_t k = 0; k < n; ++k)
      for (int c = 0; c < 2; ++c)
        EXPECT_EQ(r.get<float>(), static_cast<float>(soup.uv(soup.face_uv[soup.face_offsets[f] + k], c)));
  }
  EXPECT_EQ(r.pos, file.size());  // nothing after the last face
}

TEST(WritePlyProperties, BinaryLayoutIsExactlyTheHeaderAndTheValues) {
  testing::TempDir dir;
  for (const bool big : {false, true}) {
    SCOPED_TRACE(big ? "big endian" : "little endian");
    const std::string path = dir.file(big ? "big.ply" : "little.ply");
    write_ply(path, sample_soup(), sample_properties(),
              big ? PlyEncoding::BinaryBigEndian : PlyEncoding::BinaryLittleEndian);
    const std::string file = ::quadcover::testing::slurp(path);
    std::string header = kHeader;
    if (big) header.replace(header.find("little"), 6, "big");
    ASSERT_EQ(file.compare(0, header.size(), header), 0) << file.substr(0, header.size());
    expect_body(file, header.size(), big);
  }
}

TEST(WritePlyProperties, AsciiHasOneLinePerElement) {
  testing::TempDir dir;
  write_ply(dir.file("a.ply"), sample_soup(), sample_properties(), PlyEncoding::Ascii);
  std::istringstream in(::quadcover::testing::slurp(dir.file("a.ply")));
  std::string line;
  while (std::getline(in, line) && line != "end_header") {
  }
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 9u);
  EXPECT_EQ(lines[4], "1 1 0.5 0 4");
  EXPECT_EQ(lines[3], "0 1 0 0.33333334 3");  // float32 of 1/3 in its shortest form
  EXPECT_EQ(lines[6], "4 0 1 4 3 8 0.1 0.2 1.5 -2.25 0.001 3 0.33333334 7");
  EXPECT_EQ(lines[8], "3 3 4 5 0");
}

TEST(WritePlyProperties, ReaderStillReadsPositionsAndFaces) {
  testing::TempDir dir;
  for (const PlyEncoding e : {PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian, PlyEncoding::BinaryBigEndian}) {
    write_ply(dir.file("m.ply"), sample_soup(), sample_properties(), e);
    const PolygonSoup back = read_mesh(dir.file("m.ply"));
    EXPECT_EQ(back.positions, sample_soup().positions);
    EXPECT_EQ(back.face_vertices, sample_soup().face_vertices);
    EXPECT_EQ(back.face_offsets, sample_soup().face_offsets);
  }
}

TEST(WritePlyProperties, WithoutExtrasTheFileIsTheOldOne) {
  testing::TempDir dir;
  PolygonSoup plain = sample_soup();
  plain.uv.resize(0, 2);
  plain.face_uv.clear();
  write_ply(dir.file("p.ply"), plain);
  const std::string file = ::quadcover::testing::slurp(dir.file("p.ply"));
  EXPECT_EQ(file.find("texcoord"), std::string::npos);
  EXPECT_EQ(file.find("quality"), std::string::npos);
  // 6 vertices of 3 doubles, faces of 1 + 4n bytes
  const std::size_t body = 6 * 24 + (1 + 16) + (1 + 16) + (1 + 12);
  EXPECT_EQ(file.size(), file.find("end_header\n") + 11 + body);
}

TEST(WritePlyProperties, BadPropertiesLeaveNoFile) {
  testing::TempDir dir;
  const std::string path = dir.file("bad.ply");
  auto props = sample_properties();
  props[0].name = "x";
  EXPECT_THROW(write_ply(path, sample_soup(), props), std::invalid_argument);
  props[0].name = "two words";
  EXPECT_THROW(write_ply(path, sample_soup(), props), std::invalid_argument);
  props = sample_properties();
  props[1].values.resize(5);
  EXPECT_THROW(write_ply(path, sample_soup(), props), std::invalid_argument);
  PolygonSoup soup = sample_soup();
  soup.face_uv[3] = 4;  // outside the 4 uv rows
  EXPECT_THROW(write_ply(path, soup, sample_properties()), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace quadcover
