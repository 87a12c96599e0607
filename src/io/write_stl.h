#pragma once
// STL writer, ASCII or binary: one record per triangle with its unit normal and three corner positions.
// Binary STL stores float32, so positions are rounded to float; ASCII writes the doubles exactly. Atomic.
#include <Eigen/Core>
#include <string>

namespace quadcover {

/// Writes V (#V by 3) and triangles F (#F by 3, 0-based) as STL (binary by default).
/// \throw std::invalid_argument for an index out of range (no file is left); InputError if `path` is unwritable.
void write_stl(const std::string& path, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, bool binary = true);

}  // namespace quadcover
