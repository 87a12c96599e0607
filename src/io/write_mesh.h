#pragma once
// Mesh writers. Every writer is atomic (temporary file + rename, see atomic_file.h): on failure no partial file
// is left. \throw InputError naming the path if the file cannot be written.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "io/polygon_soup.h"

namespace quadcover {

// Numbers are written in the shortest form that reads back to the same double (exact round trip).
// Index arguments are checked: an index out of range throws std::invalid_argument and leaves no file.

/// OBJ with `v` and `f` lines. V #V by 3, F #F by 3 (0-based).
/// \throw std::invalid_argument for an index out of range; InputError if path cannot be written.
void write_obj(const std::string& path, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

/// OBJ with per-corner texture coordinates: `v`, `vt`, `f v/vt`. UV #UV by 2; FUV #F by 3 indices into UV.
/// \throw std::invalid_argument for an index out of range or FUV rows != F rows; InputError if unwritable.
void write_obj_with_uv(const std::string& path, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                       const Eigen::MatrixX2d& UV, const Eigen::MatrixX3i& FUV);

/// OBJ with polygon faces of any size (quad meshes). faces: 0-based vertex indices per face.
/// \throw std::invalid_argument for an index out of range or a face of < 3 corners; InputError if unwritable.
void write_polygon_obj(const std::string& path, const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces);

/// A polygon mesh (quad meshes) in the format the extension of `path` names: .obj, .off, .ply (binary little
/// endian), .stl (binary; it holds only triangles, so polygons are fan-triangulated); "-" writes standard output in
/// standard_stream_format() (default OBJ). Atomic. Returns the number of polygons split into triangles (STL only;
/// the caller says so), 0 otherwise.
/// \throw InputError for an unknown extension, std::invalid_argument for an index out of range or a face with
/// fewer than 3 corners (no file is left).
std::size_t write_polygon_mesh(const std::string& path, const Eigen::MatrixX3d& V,
                               const std::vector<std::vector<int>>& faces);

/// The format write_polygon_mesh writes to `path`: "obj", "off", "ply" or "stl". Call it before the work so that a
/// bad output name fails at once. \throw InputError naming the path and the supported extensions otherwise.
std::string mesh_output_format(const std::string& path);

/// OBJ of a polygon soup as read: positions, `vt` lines and `f v/vt` corners where soup.face_uv has them.
/// Soup indices must be in range (validate first); -1 in face_uv writes the corner without texture index.
/// \pre soup indices in range (validated). \throw InputError if path cannot be written.
void write_soup_obj(const std::string& path, const PolygonSoup& soup);

}  // namespace quadcover
