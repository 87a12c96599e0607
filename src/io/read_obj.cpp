#include <charconv>
#include <cmath>
#include <string_view>

#include "common/errors.h"
#include "io/read_mesh.h"
#include "io/text_scanner.h"

namespace quadcover {

PolygonSoup read_obj(const std::string& path) {
  const std::string bytes = read_file_bytes(path);
  PolygonSoup soup;
  soup.file = path;
  std::vector<double> xyz;
  xyz.reserve(bytes.size() / 12);
  std::vector<std::int64_t> corners;
  TextScanner scan(bytes);
  while (scan.next_line()) {
    std::string_view key = scan.token();
    if (key == "v") {
      double p[3];
      for (double& c : p) {
        if (!scan.number(c)) throw InputError(path, scan.line(), "vertex line needs three numeric coordinates");
      }
      xyz.insert(xyz.end(), p, p + 3);
      soup.vertex_lines.push_back(scan.line());
    } else if (key == "f") {
      corners.clear();
      const auto num_read = static_cast<std::int64_t>(xyz.size() / 3);
      std::string_view tok;
      while (!(tok = scan.token()).empty()) {
        // A corner is `v`, `v/vt`, `v//vn` or `v/vt/vn`: only the position index matters here.
        const std::string_view vtok = tok.substr(0, tok.find('/'));
        std::int64_t idx = 0;
        const auto [ptr, ec] = std::from_chars(vtok.data(), vtok.data() + vtok.size(), idx);
        if (ec != std::errc() || ptr != vtok.data() + vtok.size() || idx == 0)
          throw InputError(path, scan.line(), "bad face corner '" + std::string(tok) + "' (expected a non-zero vertex index)");
        // Positive indices are 1-based; negative ones count back from the last vertex read so far.
        corners.push_back(idx > 0 ? idx - 1 : num_read + idx);
      }
      if (corners.size() < 3)
        throw InputError(path, scan.line(), "face has " + std::to_string(corners.size()) + " corners (at least 3 needed)");
      soup.add_face(corners.data(), corners.size(), scan.line());
    }
    // Every other statement (vt, vn, g, o, s, usemtl, mtllib, l, comments) carries nothing we need.
  }
  soup.positions = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      xyz.data(), static_cast<Eigen::Index>(xyz.size() / 3), 3);
  return soup;
}

}  // namespace quadcover
