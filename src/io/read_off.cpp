// OFF reader (Geomview Object File Format): [ST][C][N]OFF header (optional; counts may follow it on the same
// line), `#V #F #E`, then one vertex per line (x y z, extras such as normals/colours/texture coordinates
// ignored) and one face per line (`n i0 ... i(n-1)`, an optional face colour after the indices ignored).
#include <algorithm>
#include <string_view>

#include "common/errors.h"
#include "io/read_mesh.h"
#include "io/text_scanner.h"

namespace quadcover {

namespace {

// Advances to the next line that holds a token; false at the end of the file.
bool next_content_line(TextScanner& scan) {
  while (scan.next_line())
    if (!scan.at_line_end()) return true;
  return false;
}

// Recognises the OFF keyword variants; sets `supported` false for the ones we do not read (4OFF, nOFF, binary).
bool is_off_keyword(std::string_view tok, bool& supported) {
  if (tok.size() < 3 || tok.substr(tok.size() - 3) != "OFF") return false;
  std::string_view prefix = tok.substr(0, tok.size() - 3);
  supported = true;
  if (prefix.starts_with("ST")) prefix.remove_prefix(2);
  if (prefix.starts_with("C")) prefix.remove_prefix(1);
  if (prefix.starts_with("N")) prefix.remove_prefix(1);
  if (prefix.starts_with("4") || prefix.starts_with("n")) {
    supported = false;  // homogeneous or n-dimensional coordinates
    prefix.remove_prefix(1);
  }
  return prefix.empty();
}

}  // namespace

PolygonSoup read_off_from_memory(std::string_view bytes, const std::string& name) {
  PolygonSoup soup;
  soup.file = name;
  TextScanner scan(bytes);
  if (!next_content_line(scan)) throw InputError(name, 0, "empty OFF file (no header or counts)");

  // Header: an optional keyword, then the three counts (on the same line or the next content line).
  TextScanner peek = scan;
  std::string_view first = peek.token();
  bool supported = true;
  if (is_off_keyword(first, supported)) {
    if (!supported)
      throw InputError(name, scan.line(),
                       "'" + std::string(first) + "' (homogeneous / n-dimensional OFF) is not supported; use plain OFF");
    scan.token();
    if (const std::string_view next = TextScanner(scan).token(); next == "BINARY")
      throw InputError(name, scan.line(), "binary OFF is not supported; use ASCII OFF, PLY or STL");
    if (scan.at_line_end() && !next_content_line(scan))
      throw InputError(name, scan.line(), "OFF file ends before the vertex/face counts");
  }
  std::int64_t nv = -1, nf = -1, ne = 0;
  if (!scan.integer(nv) || !scan.integer(nf))
    throw InputError(name, scan.line(), "expected the counts '#vertices #faces #edges' after the OFF header");
  if (!scan.at_line_end() && !scan.integer(ne))
    throw InputError(name, scan.line(), "the edge count in the OFF header is not an integer");
  if (nv < 0 || nf < 0)
    throw InputError(name, scan.line(), "negative vertex or face count in the OFF header");
  (void)ne;  // the edge count is informative only

  // Never trust the counts for allocation: a vertex line needs at least 6 bytes, a face line at least 8.
  const auto remaining = static_cast<std::int64_t>(bytes.size() - std::min(bytes.size(), scan.offset()));
  std::vector<double> xyz;
  xyz.reserve(static_cast<std::size_t>(std::min(nv, remaining / 6 + 1)) * 3);
  soup.vertex_lines.reserve(xyz.capacity() / 3);
  for (std::int64_t v = 0; v < nv; ++v) {
    if (!next_content_line(scan))
      throw InputError(name, scan.line(),
                       "file ends after " + std::to_string(v) + " of " + std::to_string(nv) + " vertices");
    double p[3];
    for (double& c : p)
      if (!scan.number(c))
        throw InputError(name, scan.line(), "vertex " + std::to_string(v) + " needs three numeric coordinates");
    xyz.insert(xyz.end(), p, p + 3);
    soup.vertex_lines.push_back(scan.line());
  }
  soup.face_offsets.reserve(static_cast<std::size_t>(std::min(nf, remaining / 8 + 1)) + 1);
  std::vector<std::int64_t> corners;
  for (std::int64_t f = 0; f < nf; ++f) {
    if (!next_content_line(scan))
      throw InputError(name, scan.line(),
                       "file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    std::int64_t n = 0;
    if (!scan.integer(n))
      throw InputError(name, scan.line(), "face " + std::to_string(f + 1) + " must start with its corner count");
    if (n < 3)
      throw InputError(name, scan.line(),
                       "face " + std::to_string(f + 1) + " has " + std::to_string(n) + " corners (at least 3 needed)");
    corners.clear();
    for (std::int64_t k = 0; k < n; ++k) {
      std::int64_t idx = 0;
      if (!scan.integer(idx))
        throw InputError(name, scan.line(),
                         "face " + std::to_string(f + 1) + " declares " + std::to_string(n) + " corners but corner " +
                             std::to_string(k + 1) + " is missing or not an integer");
      corners.push_back(idx);  // OFF indices are 0-based already
    }
    // Anything left on the line is a face colour (ignored).
    soup.add_face(corners.data(), corners.size(), scan.line());
  }
  soup.positions = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      xyz.data(), static_cast<Eigen::Index>(xyz.size() / 3), 3);
  return soup;
}

}  // namespace quadcover
