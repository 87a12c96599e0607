#pragma once
// OFF writer (ASCII): `OFF`, counts, vertices, `n i0 .. in-1` faces. Atomic (see atomic_file.h).
#include <Eigen/Core>
#include <string>

#include "io/polygon_soup.h"

namespace quadcover {

/// Writes V (#V by 3) and triangles F (#F by 3, 0-based) as ASCII OFF; numbers round-trip exactly.
/// \throw std::invalid_argument for an index out of range (no file is left); InputError if `path` is unwritable.
void write_off(const std::string& path, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

/// Writes a polygon soup (faces of any size) as ASCII OFF.
/// \throw std::invalid_argument for a face of < 3 corners or an index out of range; InputError if unwritable.
void write_off(const std::string& path, const PolygonSoup& soup);

}  // namespace quadcover
