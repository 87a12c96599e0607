#include <charconv>
#include <cmath>
#include <string_view>

#include "common/errors.h"
#include "io/read_mesh.h"
#include "io/text_scanner.h"

namespace quadcover {

namespace {

// Parses one OBJ index (1-based, or negative = relative to the `count` elements read so far) into a 0-based index.
bool parse_obj_index(std::string_view tok, std::int64_t count, std::int64_t& out) {
  std::int64_t idx = 0;
  const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), idx);
  if (ec != std::errc() || ptr != tok.data() + tok.size() || idx == 0) return false;
  out = idx > 0 ? idx - 1 : count + idx;
  return true;
}

// Up to 16 bytes of a token for a message, non-printable bytes as \xNN (random bytes stay readable).
std::string printable(std::string_view tok) {
  std::string out;
  for (const unsigned char c : tok.substr(0, 16)) {
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += std::string("\\x") + hex[c >> 4] + hex[c & 15];
    }
  }
  return tok.size() > 16 ? out + "..." : out;
}

/// One corner of an `f` line: `v`, `v/vt`, `v//vn` or `v/vt/vn`, as 0-based indices (texture -1: none).
struct FaceCorner {
  std::int64_t vertex = 0, texture = -1;
};

/// \throw InputError (file, line, the corner as written) for a bad index or a vt index not defined yet.
FaceCorner parse_face_corner(std::string_view tok, std::int64_t num_read, std::int64_t num_uv, const std::string& name,
                             long line) {
  const std::size_t slash = tok.find('/');
  FaceCorner corner;
  if (!parse_obj_index(tok.substr(0, slash), num_read, corner.vertex))
    throw InputError(name, line, "bad face corner '" + std::string(tok) + "' (expected a non-zero vertex index)");
  if (corner.vertex < 0)  // a negative (relative) index reaching before the first vertex; positive ones may point ahead
    throw InputError(name, line,
                     "face corner '" + std::string(tok) + "' refers to vertex " + std::string(tok.substr(0, slash)) +
                         " (counted back from this line) but only " + std::to_string(num_read) +
                         " vertices were defined before this line");
  if (slash == std::string_view::npos) return corner;
  const std::string_view rest = tok.substr(slash + 1);
  const std::string_view vt = rest.substr(0, rest.find('/'));
  if (vt.empty()) return corner;
  if (!parse_obj_index(vt, num_uv, corner.texture))
    throw InputError(name, line, "bad face corner '" + std::string(tok) + "' (expected a non-zero texture index)");
  if (corner.texture < 0 || corner.texture >= num_uv)
    throw InputError(name, line,
                     "face corner '" + std::string(tok) + "' refers to texture coordinate " +
                         std::to_string(corner.texture + 1) + " but only " + std::to_string(num_uv) +
                         " were defined before this line");
  return corner;
}

}  // namespace

PolygonSoup read_obj_from_memory(std::string_view bytes, const std::string& name) {
  PolygonSoup soup;
  soup.file = name;
  soup.index_base = 1;
  std::vector<double> xyz;
  xyz.reserve(bytes.size() / 16);
  std::vector<double> uvs;
  std::vector<std::int64_t> corner_uv;  // one entry per corner; dropped at the end if no corner has a `vt`
  bool any_uv = false;
  std::vector<std::int64_t> corners, uv_corners;
  TextScanner scan(bytes);
  long first_other_line = 0;  // first line with a statement we do not read, and its keyword
  std::string_view first_other;
  while (scan.next_line()) {
    const std::string_view key = scan.token();
    if (key == "v") {
      double p[3];
      for (double& c : p)
        if (!scan.number(c)) throw InputError(name, scan.line(), "vertex line needs three numeric coordinates");
      // Anything after x y z (a weight w or vertex colours) carries nothing we need.
      xyz.insert(xyz.end(), p, p + 3);
      soup.vertex_lines.push_back(scan.line());
    } else if (key == "vt") {
      double t[2] = {0, 0};
      if (!scan.number(t[0])) throw InputError(name, scan.line(), "texture coordinate line needs a numeric u");
      // v is optional in the OBJ specification (default 0); w is ignored.
      if (!scan.at_line_end() && !scan.number(t[1]))
        throw InputError(name, scan.line(), "texture coordinate v is not a number");
      uvs.insert(uvs.end(), t, t + 2);
    } else if (key == "f") {
      corners.clear();
      uv_corners.clear();
      const auto num_read = static_cast<std::int64_t>(xyz.size() / 3);
      const auto num_uv = static_cast<std::int64_t>(uvs.size() / 2);
      std::string_view tok;
      while (!(tok = scan.token()).empty()) {
        const FaceCorner corner = parse_face_corner(tok, num_read, num_uv, name, scan.line());
        corners.push_back(corner.vertex);
        uv_corners.push_back(corner.texture);
        any_uv = any_uv || corner.texture >= 0;
      }
      if (corners.size() < 3)
        throw InputError(name, scan.line(),
                         "face has " + std::to_string(corners.size()) + " corners (at least 3 needed)");
      soup.add_face(corners.data(), corners.size(), scan.line());
      corner_uv.insert(corner_uv.end(), uv_corners.begin(), uv_corners.end());
    } else if (!key.empty() && first_other_line == 0) {
      // Every other statement (vn, g, o, s, usemtl, mtllib, l, p) carries nothing we need.
      first_other_line = scan.line();
      first_other = key;
    }
  }
  // Text without a single vertex or face but with other content is not an OBJ mesh (e.g. random bytes, another
  // format under an .obj name): say so instead of reporting an empty mesh.
  if (xyz.empty() && soup.num_faces() == 0 && first_other_line > 0)
    throw InputError(name, first_other_line,
                     "not an OBJ mesh file: no 'v' or 'f' statement anywhere (this line starts with '" +
                         printable(first_other) + "')");
  soup.positions = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      xyz.data(), static_cast<Eigen::Index>(xyz.size() / 3), 3);
  if (any_uv) {
    soup.uv = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>>(
        uvs.data(), static_cast<Eigen::Index>(uvs.size() / 2), 2);
    soup.face_uv = std::move(corner_uv);
  }
  return soup;
}

PolygonSoup read_obj(const std::string& path) { return read_obj_from_memory(read_file_bytes(path), path); }

}  // namespace quadcover
