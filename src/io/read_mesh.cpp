#include <algorithm>
#include <fstream>
#include <sstream>

#include "common/errors.h"
#include "io/read_mesh.h"

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

PolygonSoup read_mesh(const std::string& path) {
  const std::string ext = file_extension(path);
  if (ext != "obj" && ext != "off" && ext != "ply" && ext != "stl")
    throw InputError(path, 0, "unsupported mesh format '." + ext + "' (supported: .obj, .off, .ply, .stl)");
  return read_mesh_from_memory(read_file_bytes(path), path, ext);
}

PolygonSoup read_off(const std::string& path) { return read_off_from_memory(read_file_bytes(path), path); }
PolygonSoup read_ply(const std::string& path) { return read_ply_from_memory(read_file_bytes(path), path); }
PolygonSoup read_stl(const std::string& path) { return read_stl_from_memory(read_file_bytes(path), path); }

}  // namespace quadcover
