#pragma once
// PLY writer: ASCII or binary (little/big endian); `vertex` with double x, y, z and `face` with
// `list uchar int vertex_indices` (polygons up to 255 corners). Atomic (see atomic_file.h).
#include <Eigen/Core>
#include <string>

#include "io/polygon_soup.h"

namespace quadcover {

enum class PlyEncoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

/// Writes V (#V by 3) and triangles F (#F by 3, 0-based). Binary encodings store positions as float64 (exact).
/// \throw std::invalid_argument for an index out of range (no file is left); InputError if `path` is unwritable.
void write_ply(const std::string& path, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
               PlyEncoding encoding = PlyEncoding::BinaryLittleEndian);

/// Writes a polygon soup. \throw std::invalid_argument for a face with more than 255 corners.
void write_ply(const std::string& path, const PolygonSoup& soup, PlyEncoding encoding = PlyEncoding::BinaryLittleEndian);

}  // namespace quadcover
