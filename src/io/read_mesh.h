#pragma once
// Mesh readers. Each returns the file's contents as a PolygonSoup with source locations and throws
// InputError (file and line, or element number for binary data) on anything it cannot parse. Validation happens
// later, in mesh/. Every reader has an in-memory entry point (`*_from_memory`, used by the fuzzers and tests);
// `name` is only used in messages. No reader trusts a count in a header: sizes are checked against the data.
#include <string>
#include <string_view>

#include "io/polygon_soup.h"

namespace quadcover {

/// Wavefront OBJ: `v`, `vt` and `f` lines (with `v/vt/vn` corners and negative relative indices); other lines
/// ignored. Texture coordinates referenced by faces fill soup.uv / soup.face_uv.
/// \throw InputError (file, line) if the file cannot be read or a line is malformed.
PolygonSoup read_obj(const std::string& path);
/// \throw InputError (name, line) for a malformed line.
PolygonSoup read_obj_from_memory(std::string_view bytes, const std::string& name);

/// OFF (also COFF/NOFF/STOFF/4OFF-less variants with per-vertex extras): header, counts, vertices, faces
/// `n i0 .. in-1` (a face colour after the indices is ignored); `#` comments anywhere.
/// \throw InputError (file, line) if the file cannot be read or is malformed.
PolygonSoup read_off(const std::string& path);
/// \throw InputError (name, line) if the bytes are malformed.
PolygonSoup read_off_from_memory(std::string_view bytes, const std::string& name);

/// PLY, ASCII or binary little/big endian: element `vertex` (x, y, z of any numeric type; other properties
/// skipped), element `face` (list property `vertex_indices` or `vertex_index`, any count and index type); other
/// elements skipped. Locations are lines (ASCII) or element numbers (binary, 1-based within the element).
/// \throw InputError (file, line or element) if the file cannot be read or is malformed.
PolygonSoup read_ply(const std::string& path);
/// \throw InputError (name, line or element) if the bytes are malformed.
PolygonSoup read_ply_from_memory(std::string_view bytes, const std::string& name);

/// STL, ASCII or binary (detected from the content). STL stores each triangle with its own corner positions:
/// identical positions are welded into one vertex, numbered in order of first appearance (deterministic).
/// \throw InputError (file, line) if the file cannot be read, is truncated or malformed.
PolygonSoup read_stl(const std::string& path);
/// \throw InputError (name, line) if the bytes are truncated or malformed.
PolygonSoup read_stl_from_memory(std::string_view bytes, const std::string& name);

/// Reads by extension (.obj, .off, .ply, .stl; case-insensitive). "-" reads standard input (once: later calls
/// return the same bytes) in the format its content shows (guess_mesh_format); messages name it "<stdin>".
/// \throw InputError for unknown extensions.
PolygonSoup read_mesh(const std::string& path);

/// The format written to "-" (standard output) by write_polygon_mesh: "obj", "off", "ply", "stl", or "" (OBJ).
/// Set once by the CLI's --format before any work. \pre none
void set_standard_stream_format(const std::string& extension);
std::string standard_stream_format();  ///< \pre none

/// The format the content looks like: "ply" (starts with `ply`), "off" (starts with an OFF keyword), "stl" ("solid"
/// or the binary size 84 + 50 n), otherwise "obj". \pre none
std::string guess_mesh_format(std::string_view bytes);
/// The same on bytes already in memory; `extension` as returned by file_extension().
/// \throw InputError for an unknown extension or malformed bytes.
PolygonSoup read_mesh_from_memory(std::string_view bytes, const std::string& name, const std::string& extension);

/// Reads the whole file into memory. \throw InputError if it cannot be opened or read.
std::string read_file_bytes(const std::string& path);

/// Lower-case extension without the dot ("obj"), or "" if none. \pre none
std::string file_extension(const std::string& path);

}  // namespace quadcover
