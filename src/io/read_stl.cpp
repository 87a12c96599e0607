// STL reader, ASCII and binary. STL has no shared vertices: every triangle lists its three corner positions.
// Corners with bit-identical positions (after mapping -0 to +0) are welded into one vertex, numbered in the order
// of their first appearance, so the result is deterministic and a closed STL becomes a closed mesh.
#include <algorithm>
#include <cstring>
#include <string_view>
#include <unordered_map>

#include "common/errors.h"
#include "io/read_mesh.h"
#include "io/text_scanner.h"
#include "io/weld_positions.h"

namespace quadcover {

namespace {

// Welds corner positions into vertices in order of first appearance.
class Welder {
 public:
  explicit Welder(std::size_t expected_corners) { index_.reserve(expected_corners / 4 + 16); }

  std::int64_t add(const double p[3], long location, PolygonSoup& soup) {
    const PositionKey key = PositionKey::of(p);
    const auto [it, inserted] = index_.try_emplace(key, static_cast<std::int64_t>(xyz_.size() / 3));
    if (inserted) {
      xyz_.insert(xyz_.end(), p, p + 3);
      soup.vertex_lines.push_back(location);
    }
    return it->second;
  }

  void finish(PolygonSoup& soup) {
    soup.positions = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
        xyz_.data(), static_cast<Eigen::Index>(xyz_.size() / 3), 3);
  }

 private:
  std::unordered_map<PositionKey, std::int64_t, PositionHash> index_;
  std::vector<double> xyz_;
};

constexpr std::size_t kBinaryHeader = 84;  // 80-byte header + uint32 triangle count
constexpr std::size_t kBinaryTriangle = 50;  // normal + 3 corners (12 float32) + uint16 attribute

bool starts_with_solid(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n')) ++i;
  return bytes.substr(i, 5) == "solid";
}

float read_float_le(const char* p) {
  unsigned char b[4];
  std::memcpy(b, p, 4);
  if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + 4);
  float f;
  std::memcpy(&f, b, 4);
  return f;
}

PolygonSoup read_binary(std::string_view bytes, const std::string& name) {
  PolygonSoup soup;
  soup.file = name;
  soup.location_unit = "element";
  soup.vertex_element = "facet";  // a welded vertex is located by the first facet that uses it
  if (bytes.size() < kBinaryHeader)
    throw InputError(name, 0, "binary STL is shorter than its 84-byte header (" + std::to_string(bytes.size()) + " bytes)");
  unsigned char c[4];
  std::memcpy(c, bytes.data() + 80, 4);
  const std::uint64_t n = std::uint64_t(c[0]) | std::uint64_t(c[1]) << 8 | std::uint64_t(c[2]) << 16 | std::uint64_t(c[3]) << 24;
  if (n > (bytes.size() - kBinaryHeader) / kBinaryTriangle)
    throw InputError(name, 0,
                     "binary STL header declares " + std::to_string(n) + " triangles (" +
                         std::to_string(kBinaryHeader + n * kBinaryTriangle) + " bytes) but the file has " +
                         std::to_string(bytes.size()) + " bytes");
  Welder weld(3 * n);
  soup.face_offsets.reserve(n + 1);
  soup.face_vertices.reserve(3 * n);
  soup.face_lines.reserve(n);
  for (std::uint64_t t = 0; t < n; ++t) {
    const char* rec = bytes.data() + kBinaryHeader + t * kBinaryTriangle + 12;  // skip the normal
    std::int64_t tri[3];
    for (int k = 0; k < 3; ++k) {
      const double p[3] = {read_float_le(rec + 12 * k), read_float_le(rec + 12 * k + 4), read_float_le(rec + 12 * k + 8)};
      tri[k] = weld.add(p, static_cast<long>(t + 1), soup);
    }
    soup.add_face(tri, 3, static_cast<long>(t + 1));
  }
  weld.finish(soup);
  return soup;
}

PolygonSoup read_ascii(std::string_view bytes, const std::string& name) {
  PolygonSoup soup;
  soup.file = name;
  Welder weld(bytes.size() / 40);
  TextScanner scan(bytes);
  std::vector<std::int64_t> corners;
  // States of the grammar: solid { facet normal n n n / outer loop / vertex x y z (3+) / endloop / endfacet } endsolid
  enum class State { BeforeSolid, InSolid, InFacet, InLoop, AfterLoop } state = State::BeforeSolid;
  long facet_line = 0;
  auto expect = [&](bool ok, const std::string& what) {
    if (!ok) throw InputError(name, scan.line(), what);
  };
  while (scan.next_line()) {
    const std::string_view key = scan.token();
    if (key.empty()) continue;
    switch (state) {
      case State::BeforeSolid:
        expect(key == "solid", "ASCII STL must start with 'solid', found '" + std::string(key) + "'");
        state = State::InSolid;
        continue;  // the rest of the line is the solid's name
      case State::InSolid:
        if (key == "endsolid") {
          state = State::BeforeSolid;
          continue;
        }
        expect(key == "facet", "expected 'facet' or 'endsolid', found '" + std::string(key) + "'");
        facet_line = scan.line();
        state = State::InFacet;
        continue;  // the facet normal is recomputed from the corners, not read
      case State::InFacet:
        expect(key == "outer" && scan.token() == "loop", "expected 'outer loop' after 'facet'");
        corners.clear();
        state = State::InLoop;
        continue;
      case State::InLoop:
        if (key == "endloop") {
          expect(corners.size() >= 3, "facet has " + std::to_string(corners.size()) + " vertices (at least 3 needed)");
          soup.add_face(corners.data(), corners.size(), facet_line);
          state = State::AfterLoop;
          continue;
        }
        {
          expect(key == "vertex", "expected 'vertex x y z' or 'endloop', found '" + std::string(key) + "'");
          double p[3];
          for (double& x : p) expect(scan.number(x), "'vertex' needs three numeric coordinates");
          corners.push_back(weld.add(p, scan.line(), soup));
        }
        continue;
      case State::AfterLoop:
        expect(key == "endfacet", "expected 'endfacet' after 'endloop'");
        state = State::InSolid;
        continue;
    }
  }
  // A missing final `endsolid` is common and harmless; an unfinished facet is not.
  if (state == State::InFacet || state == State::InLoop || state == State::AfterLoop)
    throw InputError(name, scan.line(), "ASCII STL ends inside the facet that starts on line " + std::to_string(facet_line));
  weld.finish(soup);
  return soup;
}

}  // namespace

PolygonSoup read_stl_from_memory(std::string_view bytes, const std::string& name) {
  // Binary files may also start with "solid": the exact size 84 + 50n decides first.
  if (bytes.size() >= kBinaryHeader) {
    unsigned char c[4];
    std::memcpy(c, bytes.data() + 80, 4);
    const std::uint64_t n =
        std::uint64_t(c[0]) | std::uint64_t(c[1]) << 8 | std::uint64_t(c[2]) << 16 | std::uint64_t(c[3]) << 24;
    if (bytes.size() == kBinaryHeader + n * kBinaryTriangle) return read_binary(bytes, name);
  }
  if (starts_with_solid(bytes)) return read_ascii(bytes, name);
  return read_binary(bytes, name);
}

}  // namespace quadcover
