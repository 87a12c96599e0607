#include "render/scene.h"

#include <Eigen/Geometry>

#include "common/errors.h"

namespace quadcover {

MeshScene scene_from_soup(const PolygonSoup& soup) {
  MeshScene s;
  s.V = soup.positions;
  const auto nv = static_cast<std::int64_t>(soup.num_vertices());
  const auto nuv = static_cast<std::int64_t>(soup.uv.rows());
  bool every_uv = soup.has_uv();
  std::size_t triangles = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const std::size_t n = soup.face_size(f);
    if (n < 3)
      throw InputError(soup.file, f < soup.face_lines.size() ? soup.face_lines[f] : 0,
                       "face with fewer than 3 corners");
    triangles += n - 2;
    s.all_triangles = s.all_triangles && n == 3;
    std::vector<int> poly(n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::int64_t v = soup.face_begin(f)[k];
      if (v < 0 || v >= nv)
        throw InputError(soup.file, f < soup.face_lines.size() ? soup.face_lines[f] : 0,
                         "vertex index " + std::to_string(v + 1) + " out of range");
      poly[k] = static_cast<int>(v);
      if (every_uv) {
        const std::int64_t t = soup.face_uv[static_cast<std::size_t>(soup.face_offsets[f]) + k];
        every_uv = t >= 0 && t < nuv;
      }
    }
    s.polygons.push_back(std::move(poly));
  }
  s.F.resize(static_cast<Eigen::Index>(triangles), 3);
  if (every_uv) s.uv.resize(static_cast<Eigen::Index>(triangles), 3);
  Eigen::Index row = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto& poly = s.polygons[f];
    for (std::size_t k = 1; k + 1 < poly.size(); ++k, ++row) {
      s.F.row(row) << poly[0], poly[k], poly[k + 1];
      if (every_uv) {
        const std::int64_t* t = soup.face_uv.data() + soup.face_offsets[f];
        for (int c = 0; c < 3; ++c) {
          const std::int64_t idx = t[c == 0 ? 0 : k + static_cast<std::size_t>(c) - 1];
          s.uv(row, c) = {soup.uv(idx, 0), soup.uv(idx, 1)};
        }
      }
    }
  }
  return s;
}

Eigen::VectorXd triangle_areas(const MeshScene& s) {
  Eigen::VectorXd A(s.F.rows());
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d p0 = s.V.row(s.F(f, 0)), p1 = s.V.row(s.F(f, 1)), p2 = s.V.row(s.F(f, 2));
    A[f] = 0.5 * (p1 - p0).cross(p2 - p0).norm();
  }
  return A;
}

}  // namespace quadcover
