#include "io/read_mesh.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>

#include "common/errors.h"

namespace quadcover {

std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open file for reading");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw InputError(path, 0, "cannot determine file size");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.seekg(0, std::ios::beg);
  if (size > 0 && !in.read(bytes.data(), size)) throw InputError(path, 0, "read error");
  return bytes;
}

std::string file_extension(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

PolygonSoup read_mesh_from_memory(std::string_view bytes, const std::string& name, const std::string& extension) {
  if (extension == "obj") return read_obj_from_memory(bytes, name);
  if (extension == "off") return read_off_from_memory(bytes, name);
  if (extension == "ply") return read_ply_from_memory(bytes, name);
  if (extension == "stl") return read_stl_from_memory(bytes, name);
  throw InputError(name, 0, "unsupported mesh format '." + extension + "' (supported: .obj, .off, .ply, .stl)");
}

namespace {
std::mutex g_stream_mutex;
std::string g_stream_format;

// Standard input, read on first use and kept: a command that reads its input twice gets the same mesh.
const std::string& standard_input_bytes() {
  static const std::string bytes = [] {
    std::ostringstream s;
    s << std::cin.rdbuf();
    return std::move(s).str();
  }();
  return bytes;
}

bool starts_with_word(std::string_view text, std::string_view word) {
  return text.substr(0, word.size()) == word &&
         (text.size() == word.size() || std::isspace(static_cast<unsigned char>(text[word.size()])));
}
}  // namespace

void set_standard_stream_format(const std::string& extension) {
  std::lock_guard lock(g_stream_mutex);
  g_stream_format = extension;
}

std::string standard_stream_format() {
  std::lock_guard lock(g_stream_mutex);
  return g_stream_format;
}

std::string guess_mesh_format(std::string_view bytes) {
  std::string_view text = bytes;
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  if (starts_with_word(text, "ply")) return "ply";
  for (std::string_view off : {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "4OFF", "nOFF"})
    if (starts_with_word(text, off)) return "off";
  if (starts_with_word(text, "solid")) return "stl";
  if (bytes.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + 80, 4);  // binary STL: little-endian triangle count after an 80-byte header
    if (bytes.size() == 84 + 50 * static_cast<std::uint64_t>(n)) return "stl";
  }
  return "obj";
}

PolygonSoup read_mesh(const std::string& path) {
  if (path == "-") {
    const std::string& bytes = standard_input_bytes();
    return read_mesh_from_memory(bytes, "<stdin>", guess_mesh_format(bytes));
  }
  const std::string ext = file_extension(path);
  if (ext != "obj" && ext != "off" && ext != "ply" && ext != "stl")
    throw InputError(path, 0, "unsupported mesh format '." + ext + "' (supported: .obj, .off, .ply, .stl)");
  return read_mesh_from_memory(read_file_bytes(path), path, ext);
}

PolygonSoup read_off(const std::string& path) { return read_off_from_memory(read_file_bytes(path), path); }
PolygonSoup read_ply(const std::string& path) { return read_ply_from_memory(read_file_bytes(path), path); }
PolygonSoup read_stl(const std::string& path) { return read_stl_from_memory(read_file_bytes(path), path); }

}  // namespace quadcover
