#include "io/polygon_soup.h"

namespace quadcover {

namespace {
std::string location(const std::string& file, const std::vector<long>& lines, const std::string& unit,
                     std::size_t i, const std::string& element) {
  std::string s = file.empty() ? std::string("<input>") : file;
  if (i < lines.size()) {
    if (unit == "line") return s + ":" + std::to_string(lines[i]);
    return s + ", " + element + " element " + std::to_string(lines[i]);
  }
  // In-memory soups have no source locations: name the 0-based index.
  return s + ", " + element + " " + std::to_string(i);
}
}  // namespace

std::string PolygonSoup::face_location(std::size_t f) const {
  return location(file, face_lines, location_unit, f, "face");
}

std::string PolygonSoup::vertex_location(std::size_t v) const {
  return location(file, vertex_lines, location_unit, v, vertex_element);
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

PolygonSoup PolygonSoup::from_polygons(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces) {
  PolygonSoup soup;
  soup.positions = V;
  for (const std::vector<int>& face : faces) {
    soup.face_vertices.insert(soup.face_vertices.end(), face.begin(), face.end());
    soup.face_offsets.push_back(static_cast<std::int64_t>(soup.face_vertices.size()));
  }
  return soup;
}

PolygonSoup triangulate_polygons(const PolygonSoup& soup) {
  PolygonSoup out = soup;  // the vertices and the file's numbering; the faces are written anew below
  out.face_offsets = {0};
  out.face_vertices.clear();
  out.face_uv.clear();
  out.face_lines.clear();
  const bool uv = soup.has_uv();
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const std::int64_t* c = soup.face_begin(f);
    const std::int64_t* t = uv ? soup.face_uv.data() + soup.face_offsets[f] : nullptr;
    const std::size_t n = soup.face_size(f);
    const long line = f < soup.face_lines.size() ? soup.face_lines[f] : static_cast<long>(f);
    if (n <= 3) {
      out.add_face(c, n, line);
      if (uv) out.face_uv.insert(out.face_uv.end(), t, t + n);
      continue;
    }
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const std::int64_t tri[3] = {c[0], c[k], c[k + 1]};
      out.add_face(tri, 3, line);
      if (uv) out.face_uv.insert(out.face_uv.end(), {t[0], t[k], t[k + 1]});
    }
  }
  if (soup.face_lines.empty()) out.face_lines.clear();
  return out;
}

}  // namespace quadcover
