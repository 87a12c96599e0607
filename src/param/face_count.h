#pragma once
// The face count a map predicts for its quad mesh (what the density stage aims at, DensityOptions::target_quads).
#include <Eigen/Core>

#include "mesh/mesh.h"

namespace quadcover {

/// Total parameter-space area Σ_t |area(φ(t))|: for a valid seamless map of a closed surface it equals the
/// number of quads of the extracted mesh. \pre uv is #F by 3.
double parameter_area(const Mesh& mesh, const Eigen::MatrixX3cd& uv);

/// Σ |Δφ| over the boundary edges that are not on an integer iso-line: the boundary's length in grid units where it
/// cuts cells. \pre uv is #F by 3.
double cut_boundary_length(const Mesh& mesh, const Eigen::MatrixX3cd& uv);

/// Σ |Δφ| over the boundary edges whose image is not parallel to an iso-line (its direction more than
/// `max_turn_radians` from both axes): the cut boundary length a map will have once its translations are rounded,
/// told from the map before the rounding, whose translations are not yet integers (a boundary edge along an axis
/// then usually ends on an iso-line, a slanted one cuts cells). \pre uv is #F by 3, max_turn_radians >= 0.
double slanted_boundary_length(const Mesh& mesh, const Eigen::MatrixX3cd& uv, double max_turn_radians);

/// The face count the extraction is expected to give: parameter_area plus half of cut_boundary_length (such a
/// boundary cuts about one cell per grid unit of its length, and each cut cell is a face of about half a cell's
/// area). Equal to parameter_area on closed surfaces and where the boundary is aligned to the grid.
/// \pre uv is #F by 3.
double expected_face_count(const Mesh& mesh, const Eigen::MatrixX3cd& uv);

}  // namespace quadcover
