#pragma once
// PLY writer: ASCII or binary (little/big endian); `vertex` with double x, y, z and optional per-vertex scalars,
// `face` with `list uchar int vertex_indices` (polygons up to 255 corners) and, when the soup has texture
// coordinates, `list uchar float texcoord` (u0 v0 u1 v1 ... per corner: the wedge UVs MeshLab reads; Blender 3.4's
// PLY importer reads only per-vertex s, t, so Blender users take the OBJ's vt).
// Atomic (see atomic_file.h).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "io/polygon_soup.h"

namespace quadcover {

enum class PlyEncoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

/// A per-vertex scalar written after x, y, z: `property float NAME`, or `property int NAME` (values rounded).
/// MeshLab shows a vertex property named `quality` as its per-vertex quality.
struct PlyVertexProperty {
  std::string name;
  Eigen::VectorXd values;  ///< #V
  bool integer = false;
};

/// Writes V (#V by 3) and triangles F (#F by 3, 0-based). Binary encodings store positions as float64 (exact).
/// \throw std::invalid_argument for an index out of range (no file is left); InputError if `path` is unwritable.
void write_ply(const std::string& path, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
               PlyEncoding encoding = PlyEncoding::BinaryLittleEndian);

/// Writes a polygon soup with the per-vertex `properties`. If soup.has_uv(), every face gets its corners'
/// texcoord (float32: rounded to the nearest float; a face with a corner without uv gets an empty list).
/// \throw std::invalid_argument for a face with fewer than 3 or more than 255 corners, an index out of range, a
/// property whose name is not an identifier or is x, y, z, or whose size is not #V (no file is left).
void write_ply(const std::string& path, const PolygonSoup& soup, const std::vector<PlyVertexProperty>& properties,
               PlyEncoding encoding = PlyEncoding::BinaryLittleEndian);
/// \throw as the overload above.
inline void write_ply(const std::string& path, const PolygonSoup& soup,
                      PlyEncoding encoding = PlyEncoding::BinaryLittleEndian) {
  write_ply(path, soup, {}, encoding);
}

}  // namespace quadcover
