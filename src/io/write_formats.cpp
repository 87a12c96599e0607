// OFF, PLY and STL writers (OBJ is in write_mesh.cpp).
#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <type_traits>

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

/// Properties must be PLY identifiers other than the positions, with one value per vertex; uv indices in range.
void check_ply_properties(const std::string& path, const PolygonSoup& soup,
                          const std::vector<PlyVertexProperty>& properties) {
  for (const PlyVertexProperty& p : properties) {
    const bool identifier = !p.name.empty() && std::all_of(p.name.begin(), p.name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
    if (!identifier || p.name == "x" || p.name == "y" || p.name == "z")
      throw std::invalid_argument(path + ": invalid PLY vertex property name '" + p.name + "'");
    if (p.values.size() != soup.positions.rows())
      throw std::invalid_argument(path + ": PLY vertex property '" + p.name + "' has " +
                                  std::to_string(p.values.size()) + " values for " +
                                  std::to_string(soup.num_vertices()) + " vertices");
  }
  if (!soup.has_uv()) return;
  if (soup.face_uv.size() != soup.face_vertices.size())
    throw std::invalid_argument(path + ": face_uv must have one entry per face corner");
  for (std::int64_t i : soup.face_uv)
    if (i >= soup.uv.rows())
      throw std::invalid_argument(path + ": texture coordinate index " + std::to_string(i) + " outside [0, " +
                                  std::to_string(soup.uv.rows()) + ")");
}

void put_ply_header(TextBuffer& b, const PolygonSoup& soup, const std::vector<PlyVertexProperty>& properties,
                    PlyEncoding encoding) {
  const char* format = encoding == PlyEncoding::Ascii                ? "ascii"
                       : encoding == PlyEncoding::BinaryLittleEndian ? "binary_little_endian"
                                                                     : "binary_big_endian";
  b.put("ply\nformat ").put(format).put(" 1.0\ncomment written by quadcover\nelement vertex ");
  b.num(static_cast<std::int64_t>(soup.num_vertices()));
  b.put("\nproperty double x\nproperty double y\nproperty double z\n");
  for (const PlyVertexProperty& p : properties)
    b.put(p.integer ? "property int " : "property float ").put(p.name).put('\n');
  b.put("element face ").num(static_cast<std::int64_t>(soup.num_faces()));
  b.put("\nproperty list uchar int vertex_indices\n");
  if (soup.has_uv()) b.put("property list uchar float texcoord\n");
  b.put("end_header\n");
}

/// The element values of a PLY body: binary in the file's byte order, or ASCII (one line per element).
class PlyBody {
 public:
  PlyBody(std::ostream& out, PlyEncoding encoding)
      : out_(out), text_(out), ascii_(encoding == PlyEncoding::Ascii), big_(encoding == PlyEncoding::BinaryBigEndian) {
    buf_.reserve(1 << 16);
  }
  template <class T>
  void value(T x) {
    if (!ascii_) return put_binary(buf_, x, big_);
    if (!first_) text_.put(' ');
    first_ = false;
    if constexpr (std::is_same_v<T, float>) {  // the float's own shortest form ("0.1", not 0.10000000149...)
      char tmp[32];
      text_.put(std::string_view(tmp, static_cast<std::size_t>(std::to_chars(tmp, tmp + sizeof tmp, x).ptr - tmp)));
    } else if constexpr (std::is_floating_point_v<T>) {
      text_.num(static_cast<double>(x));
    } else {
      text_.num(static_cast<std::int64_t>(x));
    }
  }
  void end_element() {
    if (ascii_) {
      text_.put('\n');
      first_ = true;
    } else if (buf_.size() >= (1 << 16)) {
      drain();
    }
  }
  void flush() {
    if (ascii_) return text_.flush();
    drain();
  }

 private:
  void drain() {
    out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    buf_.clear();
  }
  std::ostream& out_;
  TextBuffer text_;
  std::string buf_;
  bool ascii_, big_, first_ = true;
};
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

void write_ply(const std::string& path, const PolygonSoup& soup, const std::vector<PlyVertexProperty>& properties,
               PlyEncoding encoding) {
  check_soup(path, soup, 255);
  check_ply_properties(path, soup, properties);
  const bool texcoords = soup.has_uv();
  write_file_atomically(path, [&](std::ostream& out) {
    TextBuffer header(out);
    put_ply_header(header, soup, properties, encoding);
    header.flush();
    PlyBody body(out, encoding);
    for (Eigen::Index v = 0; v < soup.positions.rows(); ++v) {
      for (int c = 0; c < 3; ++c) body.value(soup.positions(v, c));
      for (const PlyVertexProperty& p : properties)
        if (p.integer)
          body.value(static_cast<std::int32_t>(std::lround(p.values[v])));
        else
          body.value(static_cast<float>(p.values[v]));
      body.end_element();
    }
    for (std::size_t f = 0; f < soup.num_faces(); ++f) {
      const std::size_t n = soup.face_size(f);
      body.value(static_cast<std::uint8_t>(n));
      for (std::size_t k = 0; k < n; ++k) body.value(static_cast<std::int32_t>(soup.face_begin(f)[k]));
      if (texcoords) {
        const std::int64_t* uv = soup.face_uv.data() + soup.face_offsets[f];
        const bool complete = std::all_of(uv, uv + n, [](std::int64_t i) { return i >= 0; });
        body.value(static_cast<std::uint8_t>(complete ? 2 * n : 0));
        for (std::size_t k = 0; complete && k < n; ++k)
          for (int c = 0; c < 2; ++c) body.value(static_cast<float>(soup.uv(uv[k], c)));
      }
      body.end_element();
    }
    body.flush();
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
