#pragma once
// Vector and frame field indices (thesis Def. 1.18, 3.2, 3.3), in quarter units. Conventions: field/frame_field.h.
#include <Eigen/Core>
#include <vector>

#include "field/frame_field.h"
#include "mesh/mesh.h"

namespace quadcover {

/// Matching index (Def. 3.2) times 4: -Σ m over the edges crossed counter-clockwise around each interior vertex
/// (our m is the thesis's -m). 0 at boundary vertices. Depends on the matching only. \return #V
/// \pre matching has #E entries.
Eigen::VectorXi matching_quarter_index(const Mesh& mesh, const Eigen::VectorXi& matching);

/// Cross-field index (Def. 3.3) times 4: (2/π)(Σ θ_e + K(p)) around each interior vertex, θ the curvature (3.4)
/// of the orthogonalized frames and K(p) = Mesh::angle_defect. 0 at boundary vertices. \return #V
/// \throw NumericalError if a sum is not within 1e-6 of a multiple of π/2 (corrupt frames: NaN or zero vectors).
Eigen::VectorXi cross_field_quarter_index(const Mesh& mesh, const FrameField& field);

/// Vector-field index (Def. 1.18) of the first frame vectors with zero matching: (Σ ∠_e + K(p)) / 2π ∈ Z.
/// ind^cross = ind(m) + this, exactly (see field/frame_field.h). \return #V
/// \pre X has #F non-zero entries. \throw NumericalError if an angle sum is not a multiple of 2π.
Eigen::VectorXi vector_field_index(const Mesh& mesh, const Eigen::VectorXcd& X);

/// Vertices whose cross-field index is not an integer (quarter index ≠ 0 mod 4), in vertex order, with their
/// cross-field quarter index. These are the branch points of the 4-sheeted covering (thesis 3.2).
/// \pre field belongs to mesh. \throw NumericalError as cross_field_quarter_index.
std::vector<BranchPoint> branch_points(const Mesh& mesh, const FrameField& field);

/// The inverse of branch_points(): per vertex the quarter index of `points`, 0 at every other vertex. \return
/// num_vertices entries. \pre every point's vertex is in [0, num_vertices).
Eigen::VectorXi quarter_index_of(int num_vertices, const std::vector<BranchPoint>& points);

}  // namespace quadcover
