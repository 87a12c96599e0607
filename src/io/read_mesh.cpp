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

PolygonSoup read_mesh(const std::string& path) {
  const std::string ext = file_extension(path);
  if (ext == "obj") return read_obj(path);
  throw InputError(path, 0, "unsupported mesh format '." + ext + "' (supported: .obj)");
}

}  // namespace quadcover
