// PLY reader (Stanford polygon file format), ASCII and binary little/big endian.
// The header declares elements and their properties; we read `vertex` (x, y, z) and `face` (the vertex index
// list) and skip every other property and element. All counts are checked against the bytes that remain.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

#include "common/errors.h"
#include "io/read_mesh.h"
#include "io/text_scanner.h"

namespace quadcover {

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64 };
/// The C++ type of each PlyType, in the enum's order.
using PlyCppTypes = std::tuple<std::int8_t, std::uint8_t, std::int16_t, std::uint16_t, std::int32_t, std::uint32_t,
                               std::int64_t, std::uint64_t, float, double>;

bool parse_type(std::string_view s, PlyType& t) {
  static constexpr std::pair<std::string_view, PlyType> kNames[] = {
      {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"int64", PlyType::Int64},   {"uint64", PlyType::UInt64},   {"float", PlyType::Float32},
      {"float32", PlyType::Float32}, {"double", PlyType::Float64}, {"float64", PlyType::Float64}};
  for (const auto& [n, type] : kNames)
    if (n == s) {
      t = type;
      return true;
    }
  return false;
}

std::size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Int64: case PlyType::UInt64: case PlyType::Float64: return 8;
  }
  return 1;
}

bool is_float(PlyType t) { return t == PlyType::Float32 || t == PlyType::Float64; }

struct PlyProperty {
  std::string name;
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;  // lists only
  PlyType type = PlyType::Float32;      // scalar type, or the list's item type
};

struct PlyElement {
  std::string name;
  std::int64_t count = 0;
  long header_line = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { Ascii, BinaryLittle, BinaryBig };

// Reads binary values with bounds checks; every failure names the element and its 1-based number.
class BinaryCursor {
 public:
  BinaryCursor(std::string_view data, std::size_t pos, bool big_endian, const std::string& file)
      : data_(data), pos_(pos), swap_(big_endian != (std::endian::native == std::endian::big)), file_(file) {}

  std::size_t remaining() const { return data_.size() - pos_; }

  /// The element being read, for messages: "<name> element <i+1>".
  void set_context(const std::string* element, std::int64_t i) {
    element_ = element;
    index_ = i;
  }
  std::string where() const { return *element_ + " element " + std::to_string(index_ + 1); }
  [[noreturn]] void fail(const std::string& what) const { throw InputError(file_, 0, where() + ": " + what); }

  void need(std::size_t n) const {
    if (n > remaining())
      fail("binary data ends early (needs " + std::to_string(n) + " more bytes at byte offset " +
           std::to_string(pos_) + ", file has " + std::to_string(remaining()) + " left)");
  }
  void skip(std::size_t n) {
    need(n);
    pos_ += n;
  }

  template <class T>
  T raw() {
    T value;
    unsigned char buf[sizeof(T)];
    std::memcpy(buf, data_.data() + pos_, sizeof(T));
    if (swap_) std::reverse(buf, buf + sizeof(T));
    std::memcpy(&value, buf, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }

  /// Reads one value of type t and hands it to f in its own C++ type (PlyCppTypes, in PlyType's order).
  template <class F>
  auto read_as(PlyType t, F&& f) {
    need(type_size(t));
    return read_as(static_cast<std::size_t>(t), f, std::make_index_sequence<std::tuple_size_v<PlyCppTypes>>{});
  }
  template <class F, std::size_t... I>
  auto read_as(std::size_t t, F& f, std::index_sequence<I...>) {
    decltype(f(std::uint8_t{0})) value{};
    ((t == I && (value = f(raw<std::tuple_element_t<I, PlyCppTypes>>()), true)) || ...);
    return value;
  }

  double as_double(PlyType t) {
    return read_as(t, [](auto v) { return static_cast<double>(v); });
  }

  /// An integer value (list counts and indices); floating-point values must be integral.
  std::int64_t as_int(PlyType t) {
    return read_as(t, [this](auto v) -> std::int64_t {
      using T = decltype(v);
      if constexpr (std::is_floating_point_v<T>) {
        const double d = v;
        if (!(std::abs(d) < 9.0e18) || d != std::floor(d))
          fail("index value " + std::to_string(d) + " is not an integer");
        return static_cast<std::int64_t>(d);
      } else if constexpr (std::is_same_v<T, std::uint64_t>) {
        // Beyond int64: keep it out of range (validation reports the index) without overflowing.
        return v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())
                   ? std::numeric_limits<std::int64_t>::max()
                   : static_cast<std::int64_t>(v);
      } else {
        return static_cast<std::int64_t>(v);
      }
    });
  }

 private:
  std::string_view data_;
  std::size_t pos_;
  bool swap_;
  const std::string& file_;
  const std::string* element_ = nullptr;
  std::int64_t index_ = 0;
};

// Integer-valued token of an ASCII list (count or index); floats with integral value are accepted.
bool ascii_int(TextScanner& scan, std::int64_t& out) {
  TextScanner copy = scan;
  if (scan.integer(out)) return true;
  double d = 0;
  if (!copy.number(d) || !(std::abs(d) < 9.0e18) || d != std::floor(d)) return false;
  scan = copy;
  out = static_cast<std::int64_t>(d);
  return true;
}

struct Header {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;
  long data_line = 0;  // number of the header's last line
};

Header parse_header(std::string_view bytes, const std::string& name) {
  Header h;
  TextScanner scan(bytes);
  if (!scan.next_line() || scan.token() != "ply") throw InputError(name, 1, "not a PLY file (first line must be 'ply')");
  bool have_format = false;
  while (true) {
    if (!scan.next_line()) throw InputError(name, scan.line(), "PLY header has no 'end_header' line");
    const std::string_view key = scan.token();
    if (key.empty() || key == "comment" || key == "obj_info") continue;
    if (key == "end_header") break;
    if (key == "format") {
      const std::string_view f = scan.token();
      if (f == "ascii") h.format = PlyFormat::Ascii;
      else if (f == "binary_little_endian") h.format = PlyFormat::BinaryLittle;
      else if (f == "binary_big_endian") h.format = PlyFormat::BinaryBig;
      else throw InputError(name, scan.line(), "unknown PLY format '" + std::string(f) + "'");
      have_format = true;
    } else if (key == "element") {
      PlyElement e;
      e.name = std::string(scan.token());
      e.header_line = scan.line();
      if (e.name.empty() || !scan.integer(e.count) || e.count < 0)
        throw InputError(name, scan.line(), "PLY element line must be 'element NAME COUNT' with COUNT >= 0");
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) throw InputError(name, scan.line(), "PLY property declared before any element");
      PlyProperty p;
      std::string_view t = scan.token();
      if (t == "list") {
        p.is_list = true;
        if (!parse_type(scan.token(), p.count_type) || !parse_type(scan.token(), p.type))
          throw InputError(name, scan.line(), "PLY list property must be 'property list COUNT_TYPE ITEM_TYPE NAME'");
        if (is_float(p.count_type))
          throw InputError(name, scan.line(), "PLY list count type must be an integer type");
      } else if (!parse_type(t, p.type)) {
        throw InputError(name, scan.line(), "unknown PLY property type '" + std::string(t) + "'");
      }
      p.name = std::string(scan.token());
      if (p.name.empty()) throw InputError(name, scan.line(), "PLY property has no name");
      h.elements.back().properties.push_back(std::move(p));
    } else {
      throw InputError(name, scan.line(), "unexpected PLY header line starting with '" + std::string(key) + "'");
    }
  }
  if (!have_format) throw InputError(name, scan.line(), "PLY header has no 'format' line");
  h.data_offset = std::min(scan.offset(), bytes.size());
  h.data_line = scan.line();
  return h;
}

// Which properties of an element we keep: index of x/y/z (vertex) or of the index list (face), -1 if absent.
struct Roles {
  int x = -1, y = -1, z = -1, list = -1;
};

Roles find_roles(const PlyElement& e, const std::string& name) {
  Roles r;
  for (int i = 0; i < static_cast<int>(e.properties.size()); ++i) {
    const PlyProperty& p = e.properties[static_cast<std::size_t>(i)];
    if (e.name == "vertex" && !p.is_list) {
      if (p.name == "x") r.x = i;
      if (p.name == "y") r.y = i;
      if (p.name == "z") r.z = i;
    }
    if (e.name == "face" && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) r.list = i;
  }
  if (e.name == "vertex" && (r.x < 0 || r.y < 0 || r.z < 0))
    throw InputError(name, e.header_line, "PLY element 'vertex' lacks one of the properties x, y, z");
  if (e.name == "face" && r.list < 0)
    throw InputError(name, e.header_line, "PLY element 'face' has no list property 'vertex_indices' or 'vertex_index'");
  return r;
}

// Smallest number of bytes one instance of the element can take in binary form (lists counted as empty).
std::size_t min_binary_size(const PlyElement& e) {
  std::size_t s = 0;
  for (const auto& p : e.properties) s += type_size(p.is_list ? p.count_type : p.type);
  return s;
}

void read_binary(std::string_view bytes, const Header& h, const std::string& name, PolygonSoup& soup,
                 std::vector<double>& xyz) {
  BinaryCursor cur(bytes, h.data_offset, h.format == PlyFormat::BinaryBig, name);
  std::vector<std::int64_t> corners;
  for (const PlyElement& e : h.elements) {
    const Roles roles = find_roles(e, name);
    const std::size_t min_size = min_binary_size(e);
    if (e.properties.empty()) continue;  // no data at all (and no way to run long on a huge count)
    // The header's count must fit into what is left of the file.
    if (static_cast<std::uint64_t>(e.count) > cur.remaining() / min_size)
      throw InputError(name, e.header_line,
                       "PLY header declares " + std::to_string(e.count) + " " + e.name + " elements of at least " +
                           std::to_string(min_size) + " bytes each, but only " + std::to_string(cur.remaining()) +
                           " bytes of data remain");
    const bool fixed = std::none_of(e.properties.begin(), e.properties.end(), [](const auto& p) { return p.is_list; });
    if (e.name == "vertex") xyz.reserve(static_cast<std::size_t>(e.count) * 3);
    if (e.name == "face") soup.face_offsets.reserve(static_cast<std::size_t>(e.count) + 1);
    if (e.name != "vertex" && e.name != "face" && fixed) {
      cur.set_context(&e.name, 0);
      cur.skip(min_size * static_cast<std::size_t>(e.count));
      continue;
    }
    for (std::int64_t i = 0; i < e.count; ++i) {
      cur.set_context(&e.name, i);
      double p[3] = {0, 0, 0};
      corners.clear();
      for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
        const PlyProperty& prop = e.properties[static_cast<std::size_t>(k)];
        if (!prop.is_list) {
          if (k == roles.x || k == roles.y || k == roles.z)
            p[k == roles.x ? 0 : k == roles.y ? 1 : 2] = cur.as_double(prop.type);
          else
            cur.skip(type_size(prop.type));
          continue;
        }
        const std::int64_t n = cur.as_int(prop.count_type);
        if (n < 0) cur.fail("negative list length " + std::to_string(n));
        const std::size_t item = type_size(prop.type);
        if (static_cast<std::uint64_t>(n) > cur.remaining() / item)
          cur.fail("list of " + std::to_string(n) + " items runs past the end of the file");
        if (k != roles.list) {
          cur.skip(static_cast<std::size_t>(n) * item);
          continue;
        }
        if (n < 3) cur.fail("face has " + std::to_string(n) + " corners (at least 3 needed)");
        for (std::int64_t c = 0; c < n; ++c) corners.push_back(cur.as_int(prop.type));
      }
      if (e.name == "vertex") {
        xyz.insert(xyz.end(), p, p + 3);
        soup.vertex_lines.push_back(static_cast<long>(i + 1));
      } else if (e.name == "face") {
        soup.add_face(corners.data(), corners.size(), static_cast<long>(i + 1));
      }
    }
  }
}

void read_ascii(std::string_view bytes, const Header& h, const std::string& name, PolygonSoup& soup,
                std::vector<double>& xyz) {
  TextScanner scan(bytes.substr(h.data_offset));
  const long line0 = h.data_line;  // scanner lines are relative to the end of the header
  std::vector<std::int64_t> corners;
  for (const PlyElement& e : h.elements) {
    const Roles roles = find_roles(e, name);
    const auto remaining = static_cast<std::int64_t>(bytes.size() - h.data_offset);
    // One element per line: at least two bytes each. Reserve no more than the data can hold.
    const auto cap = static_cast<std::size_t>(std::min(e.count, remaining / 2 + 1));
    if (e.name == "vertex") xyz.reserve(cap * 3);
    if (e.name == "face") soup.face_offsets.reserve(cap + 1);
    for (std::int64_t i = 0; i < e.count; ++i) {
      bool got = false;
      while ((got = scan.next_line()) && scan.at_line_end()) {
      }
      if (!got)
        throw InputError(name, line0 + scan.line(),
                         "file ends after " + std::to_string(i) + " of " + std::to_string(e.count) + " " + e.name +
                             " elements");
      const long line = line0 + scan.line();
      double p[3] = {0, 0, 0};
      corners.clear();
      for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
        const PlyProperty& prop = e.properties[static_cast<std::size_t>(k)];
        if (!prop.is_list) {
          double value = 0;
          if (!scan.number(value))
            throw InputError(name, line,
                             e.name + " element " + std::to_string(i + 1) + ": property '" + prop.name +
                                 "' is missing or not a number");
          if (k == roles.x) p[0] = value;
          if (k == roles.y) p[1] = value;
          if (k == roles.z) p[2] = value;
          continue;
        }
        std::int64_t n = 0;
        if (!ascii_int(scan, n) || n < 0)
          throw InputError(name, line,
                           e.name + " element " + std::to_string(i + 1) + ": list '" + prop.name +
                               "' must start with a non-negative item count");
        if (k == roles.list && n < 3)
          throw InputError(
              name, line,
              "face " + std::to_string(i + 1) + " has " + std::to_string(n) + " corners (at least 3 needed)");
        for (std::int64_t c = 0; c < n; ++c) {
          std::int64_t idx = 0;
          double skipped = 0;
          const bool ok = k == roles.list ? ascii_int(scan, idx) : scan.number(skipped);
          if (!ok)
            throw InputError(name, line,
                             e.name + " element " + std::to_string(i + 1) + ": list '" + prop.name + "' declares " +
                                 std::to_string(n) + " items but item " + std::to_string(c) +
                                 " is missing or not a number");
          if (k == roles.list) corners.push_back(idx);
        }
      }
      if (!scan.at_line_end())
        throw InputError(name, line,
                         e.name + " element " + std::to_string(i + 1) + " has more values than the header declares");
      if (e.name == "vertex") {
        xyz.insert(xyz.end(), p, p + 3);
        soup.vertex_lines.push_back(line);
      } else if (e.name == "face") {
        soup.add_face(corners.data(), corners.size(), line);
      }
    }
  }
}

}  // namespace

PolygonSoup read_ply_from_memory(std::string_view bytes, const std::string& name) {
  const Header h = parse_header(bytes, name);
  int vertex_elements = 0, face_elements = 0;
  for (const auto& e : h.elements) {
    vertex_elements += e.name == "vertex";
    face_elements += e.name == "face";
  }
  if (vertex_elements != 1) throw InputError(name, 0, "PLY file must declare exactly one 'vertex' element");
  if (face_elements > 1) throw InputError(name, 0, "PLY file declares more than one 'face' element");
  for (const auto& e : h.elements) find_roles(e, name);  // report missing x/y/z or index lists before any data
  PolygonSoup soup;
  soup.file = name;
  std::vector<double> xyz;
  if (h.format == PlyFormat::Ascii) {
    read_ascii(bytes, h, name, soup, xyz);
  } else {
    soup.location_unit = "element";
    read_binary(bytes, h, name, soup, xyz);
  }
  soup.positions = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      xyz.data(), static_cast<Eigen::Index>(xyz.size() / 3), 3);
  return soup;
}

}  // namespace quadcover
