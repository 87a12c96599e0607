// OFF, PLY and STL writers (OBJ is in write_mesh.cpp).
#include <algorithm>
#include <bit>
#include <cstring>
#include <Eigen/Geometry>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/text_format.h"
#include "io/write_off.h"
#include "io/write_ply.h"
#include "io/write_stl.h"

namespace quadcover {

namespace {

using detail::TextBuffer;

void check_soup(const std::string& path, const PolygonSoup& soup, std::size_t max_corners) {
  const auto nv = static_cast<std::int64_t>(soup.num_vertices());
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const std::size_t n = soup.face_size(f);
    if (n < 3 || n > max_corners)
      throw std::invalid_argument(path + ": face " + std::to_string(f) + " has " + std::to_string(n) +
                                  " corners (this format takes 3 to " + std::to_string(max_corners) + ")");
    for (std::size_t k = 0; k < n; ++k) {
      const std::int64_t v = soup.face_begin(f)[k];
      if (v < 0 || v >= nv)
        throw std::invalid_argument(path + ": face " + std::to_string(f) + " has vertex index " + std::to_string(v) +
                                    " outside [0, " + std::to_string(nv) + ")");
    }
  }
}

PolygonSoup soup_of(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) { return PolygonSoup::from_triangles(V, F); }

// Appends the bytes of a value in the requested byte order.
template <class T>
void put_binary(std::string& buf, T value, bool big_endian) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
  buf.append(reinterpret_cast<const char*>(b), sizeof(T));
}

// The body OFF and ASCII PLY share: one "x y z" line per vertex, then one "n i0 .. in-1" line per face.
void put_ascii_body(TextBuffer& b, const PolygonSoup& soup) {
  for (Eigen::Index v = 0; v < soup.positions.rows(); ++v)
    b.num(soup.positions(v, 0)).put(' ').num(soup.positions(v, 1)).put(' ').num(soup.positions(v, 2)).put('\n');
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    b.num(static_cast<std::int64_t>(soup.face_size(f)));
    for (std::size_t k = 0; k < soup.face_size(f); ++k) b.put(' ').num(soup.face_begin(f)[k]);
    b.put('\n');
  }
}

}  // namespace

void write_off(const std::string& path, const PolygonSoup& soup) {
  check_soup(path, soup, static_cast<std::size_t>(-1));
  write_file_atomically(path, [&](std::ostream& out) {
    TextBuffer b(out);
    b.put("OFF\n").num(static_cast<std::int64_t>(soup.num_vertices())).put(' ');
    b.num(static_cast<std::int64_t>(soup.num_faces())).put(" 0\n");
    put_ascii_body(b, soup);
    b.flush();
  });
}

void write_off(const std::string& path, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  write_off(path, soup_of(V, F));
}

void write_ply(const std::string& path, const PolygonSoup& soup, PlyEncoding encoding) {
  check_soup(path, soup, 255);
  write_file_atomically(path, [&](std::ostream& out) {
    const char* format = encoding == PlyEncoding::Ascii                ? "ascii"
                         : encoding == PlyEncoding::BinaryLittleEndian ? "binary_little_endian"
                                                                       : "binary_big_endian";
    TextBuffer b(out);
    b.put("ply\nformat ").put(format).put(" 1.0\ncomment written by quadcover\nelement vertex ");
    b.num(static_cast<std::int64_t>(soup.num_vertices()));
    b.put("\nproperty double x\nproperty double y\nproperty double z\nelement face ");
    b.num(static_cast<std::int64_t>(soup.num_faces()));
    b.put("\nproperty list uchar int vertex_indices\nend_header\n");
    if (encoding == PlyEncoding::Ascii) {
      put_ascii_body(b, soup);
      b.flush();
      return;
    }
    b.flush();
    const bool big = encoding == PlyEncoding::BinaryBigEndian;
    std::string buf;
    buf.reserve(1 << 16);
    auto drain = [&](bool force) {
      if (force || buf.size() >= (1 << 16)) {
        out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
        buf.clear();
      }
    };
    for (Eigen::Index v = 0; v < soup.positions.rows(); ++v) {
      for (int c = 0; c < 3; ++c) put_binary(buf, soup.positions(v, c), big);
      drain(false);
    }
    for (std::size_t f = 0; f < soup.num_faces(); ++f) {
      put_binary(buf, static_cast<std::uint8_t>(soup.face_size(f)), big);
      for (std::size_t k = 0; k < soup.face_size(f); ++k)
        put_binary(buf, static_cast<std::int32_t>(soup.face_begin(f)[k]), big);
      drain(false);
    }
    drain(true);
  });
}

void write_ply(const std::string& path, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, PlyEncoding encoding) {
  write_ply(path, soup_of(V, F), encoding);
}

void write_stl(const std::string& path, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, bool binary) {
  check_soup(path, soup_of(V, F), 3);
  auto normal = [&](Eigen::Index f) {
    const Eigen::Vector3d p0 = V.row(F(f, 0)), p1 = V.row(F(f, 1)), p2 = V.row(F(f, 2));
    const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
    const double len = n.norm();
    return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
  };
  write_file_atomically(path, [&](std::ostream& out) {
    if (!binary) {
      TextBuffer b(out);
      b.put("solid quadcover\n");
      for (Eigen::Index f = 0; f < F.rows(); ++f) {
        const Eigen::Vector3d n = normal(f);
        b.put("facet normal ").num(n.x()).put(' ').num(n.y()).put(' ').num(n.z()).put("\n outer loop\n");
        for (int k = 0; k < 3; ++k)
          b.put("  vertex ").num(V(F(f, k), 0)).put(' ').num(V(F(f, k), 1)).put(' ').num(V(F(f, k), 2)).put('\n');
        b.put(" endloop\nendfacet\n");
      }
      b.put("endsolid quadcover\n");
      b.flush();
      return;
    }
    std::string buf(80, '\0');
    const char title[] = "binary STL written by quadcover";
    std::memcpy(buf.data(), title, sizeof title - 1);
    put_binary(buf, static_cast<std::uint32_t>(F.rows()), false);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const Eigen::Vector3d n = normal(f);
      for (int c = 0; c < 3; ++c) put_binary(buf, static_cast<float>(n[c]), false);
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) put_binary(buf, static_cast<float>(V(F(f, k), c)), false);
      put_binary(buf, std::uint16_t{0}, false);
      if (buf.size() >= (1 << 16)) {
        out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
        buf.clear();
      }
    }
    out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
  });
}

}  // namespace quadcover
