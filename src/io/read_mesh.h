#pragma once
// Mesh readers. Each returns the file's contents as a PolygonSoup with source locations and throws
// InputError (file and line) on anything it cannot parse. Validation happens later, in mesh/.
#include <string>

#include "io/polygon_soup.h"

namespace quadcover {

/// Wavefront OBJ: `v` and `f` lines (with `v/vt/vn` corners and negative relative indices); other lines ignored.
PolygonSoup read_obj(const std::string& path);

/// Reads by extension (.obj, .off, .ply, .stl; case-insensitive). \throw InputError for unknown extensions.
PolygonSoup read_mesh(const std::string& path);

/// Reads the whole file into memory. \throw InputError if it cannot be opened or read.
std::string read_file_bytes(const std::string& path);

/// Lower-case extension without the dot ("obj"), or "" if none.
std::string file_extension(const std::string& path);

}  // namespace quadcover
