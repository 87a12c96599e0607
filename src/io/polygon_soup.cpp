#include "io/polygon_soup.h"

namespace quadcover {

namespace {
std::string location(const std::string& file, const std::vector<long>& lines, const std::string& unit,
                     std::size_t i, const char* what) {
  std::string s = file.empty() ? std::string("<input>") : file;
  if (i < lines.size()) {
    if (unit == "line") return s + ":" + std::to_string(lines[i]);
    return s + ", " + what + " " + std::to_string(lines[i]);
  }
  return s + ", " + what + " " + std::to_string(i);
}
}  // namespace

std::string PolygonSoup::face_location(std::size_t f) const {
  return location(file, face_lines, location_unit, f, "face");
}

std::string PolygonSoup::vertex_location(std::size_t v) const {
  return location(file, vertex_lines, location_unit, v, "vertex");
}

PolygonSoup PolygonSoup::from_triangles(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  PolygonSoup soup;
  soup.positions = V;
  soup.face_vertices.reserve(static_cast<std::size_t>(F.rows()) * 3);
  soup.face_offsets.reserve(static_cast<std::size_t>(F.rows()) + 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) soup.face_vertices.push_back(F(f, k));
    soup.face_offsets.push_back(static_cast<std::int64_t>(soup.face_vertices.size()));
  }
  return soup;
}

PolygonSoup triangulate_polygons(const PolygonSoup& soup) {
  PolygonSoup out;
  out.file = soup.file;
  out.positions = soup.positions;
  out.vertex_lines = soup.vertex_lines;
  out.location_unit = soup.location_unit;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const std::int64_t* c = soup.face_begin(f);
    const std::size_t n = soup.face_size(f);
    const long line = f < soup.face_lines.size() ? soup.face_lines[f] : static_cast<long>(f);
    if (n <= 3) {
      out.add_face(c, n, line);
      continue;
    }
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const std::int64_t tri[3] = {c[0], c[k], c[k + 1]};
      out.add_face(tri, 3, line);
    }
  }
  if (soup.face_lines.empty()) out.face_lines.clear();
  return out;
}

}  // namespace quadcover
