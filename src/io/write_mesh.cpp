#include "io/write_mesh.h"

#include <stdexcept>

#include "common/errors.h"
#include "io/atomic_file.h"
#include "io/read_mesh.h"
#include "io/text_format.h"
#include "io/write_off.h"
#include "io/write_ply.h"
#include "io/write_stl.h"

namespace quadcover {

namespace {

using detail::TextBuffer;

void check_index(const std::string& path, std::int64_t i, std::int64_t n, const char* what, std::int64_t face) {
  if (i < 0 || i >= n)
    throw std::invalid_argument(path + ": face " + std::to_string(face) + " has " + what + " index " +
                                std::to_string(i) + " outside [0, " + std::to_string(n) + ")");
}

void put_vertices(TextBuffer& b, const Eigen::MatrixX3d& V) {
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    b.put("v ").num(V(v, 0)).put(' ').num(V(v, 1)).put(' ').num(V(v, 2)).put('\n');
}

void put_uvs(TextBuffer& b, const Eigen::MatrixX2d& UV) {
  for (Eigen::Index t = 0; t < UV.rows(); ++t) b.put("vt ").num(UV(t, 0)).put(' ').num(UV(t, 1)).put('\n');
}

}  // namespace

void write_obj(const std::string& path, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  write_file_atomically(path, [&](std::ostream& out) {
    TextBuffer b(out);
    put_vertices(b, V);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      b.put('f');
      for (int k = 0; k < 3; ++k) {
        check_index(path, F(f, k), V.rows(), "vertex", f);
        b.put(' ').num(F(f, k) + 1);
      }
      b.put('\n');
    }
    b.flush();
  });
}

void write_obj_with_uv(const std::string& path, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                       const Eigen::MatrixX2d& UV, const Eigen::MatrixX3i& FUV) {
  if (FUV.rows() != F.rows())
    throw std::invalid_argument(path + ": FUV has " + std::to_string(FUV.rows()) + " rows but F has " +
                                std::to_string(F.rows()));
  write_file_atomically(path, [&](std::ostream& out) {
    TextBuffer b(out);
    put_vertices(b, V);
    put_uvs(b, UV);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      b.put('f');
      for (int k = 0; k < 3; ++k) {
        check_index(path, F(f, k), V.rows(), "vertex", f);
        check_index(path, FUV(f, k), UV.rows(), "texture", f);
        b.put(' ').num(F(f, k) + 1).put('/').num(FUV(f, k) + 1);
      }
      b.put('\n');
    }
    b.flush();
  });
}

void write_polygon_obj(const std::string& path, const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces) {
  write_file_atomically(path, [&](std::ostream& out) {
    TextBuffer b(out);
    put_vertices(b, V);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (faces[f].size() < 3)
        throw std::invalid_argument(path + ": face " + std::to_string(f) + " has fewer than 3 corners");
      b.put('f');
      for (int v : faces[f]) {
        check_index(path, v, V.rows(), "vertex", static_cast<std::int64_t>(f));
        b.put(' ').num(v + 1);
      }
      b.put('\n');
    }
    b.flush();
  });
}

void write_soup_obj(const std::string& path, const PolygonSoup& soup) {
  write_file_atomically(path, [&](std::ostream& out) {
    TextBuffer b(out);
    put_vertices(b, soup.positions);
    put_uvs(b, soup.uv);
    const auto nv = static_cast<std::int64_t>(soup.num_vertices());
    const auto nt = static_cast<std::int64_t>(soup.uv.rows());
    for (std::size_t f = 0; f < soup.num_faces(); ++f) {
      b.put('f');
      for (auto i = soup.face_offsets[f]; i < soup.face_offsets[f + 1]; ++i) {
        const auto idx = static_cast<std::size_t>(i);
        check_index(path, soup.face_vertices[idx], nv, "vertex", static_cast<std::int64_t>(f));
        b.put(' ').num(soup.face_vertices[idx] + 1);
        if (soup.has_uv() && soup.face_uv[idx] >= 0) {
          check_index(path, soup.face_uv[idx], nt, "texture", static_cast<std::int64_t>(f));
          b.put('/').num(soup.face_uv[idx] + 1);
        }
      }
      b.put('\n');
    }
    b.flush();
  });
}

std::string mesh_output_format(const std::string& path) {
  const std::string ext = path == "-" ? standard_stream_format() : file_extension(path);
  if (path == "-" && ext.empty()) return "obj";
  if (ext == "obj" || ext == "off" || ext == "ply" || ext == "stl") return ext;
  throw InputError(path, 0,
                   (ext.empty() ? std::string("output has no extension") : "unsupported output format '." + ext + "'") +
                       " (supported: .obj, .off, .ply, .stl)");
}

std::size_t write_polygon_mesh(const std::string& path, const Eigen::MatrixX3d& V,
                               const std::vector<std::vector<int>>& faces) {
  const std::string format = mesh_output_format(path);
  if (format == "obj") {
    write_polygon_obj(path, V, faces);
    return 0;
  }
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (faces[f].size() < 3)
      throw std::invalid_argument(path + ": face " + std::to_string(f) + " has fewer than 3 corners");
  const PolygonSoup soup = PolygonSoup::from_polygons(V, faces);
  if (format == "off") {
    write_off(path, soup);
    return 0;
  }
  if (format == "ply") {
    write_ply(path, soup);
    return 0;
  }
  std::size_t polygons = 0;
  for (const auto& face : faces) polygons += face.size() > 3;
  const PolygonSoup triangles = triangulate_polygons(soup);
  Eigen::MatrixX3i F(static_cast<Eigen::Index>(triangles.num_faces()), 3);
  for (std::size_t t = 0; t < triangles.num_faces(); ++t)
    for (int k = 0; k < 3; ++k) F(static_cast<Eigen::Index>(t), k) = static_cast<int>(triangles.face_begin(t)[k]);
  write_stl(path, V, F);
  return polygons;
}

}  // namespace quadcover
