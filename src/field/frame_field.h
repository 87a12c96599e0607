#pragma once
// Frame fields (thesis 3.1): per face a frame (X_t, Y_t) of two tangent vectors, plus an integer matching per
// edge (Def. 3.1). Cross fields are the orthonormal case Y_t = J X_t.
//
// Conventions (fixed project-wide; the cover, param and optimize stages rely on them):
//  - X_t, Y_t are complex numbers in face t's basis (see Mesh); J is multiplication by i.
//  - The matching lives on the edge e with its fixed orientation s = EF(e,0) -> t = EF(e,1) (so m_ts = -m_st is
//    implicit). m_e counts counter-clockwise quarter turns: X_t is matched with J^{m_e} ρ_e X_s, where ρ_e is the
//    transport of Mesh::edge_transport(); for a general frame, (X_t, Y_t) is matched with
//    ρ_e · R'^{m_e}(X_s, Y_s), R'(X, Y) = (Y, -X), which is J applied to both vectors when Y = JX.
//    (The thesis's R(X,Y) = (-Y,X) turns the other way, so its m_st is our -m_e.)
//  - Curvature (3.4): θ_e = arg(X_t / (i^{m_e} ρ_e X_s)) ∈ (-π, π], the residual rotation from the matched vector
//    of s to X_t (for a general frame X is replaced by the first vector of the orthogonalized frame (X,Y)^⊥).
//    It equals the thesis's ∠(X_s,X_t) - (π/2)m_e whenever that lies in (-π, π], e.g. always for the straightest
//    matching (5.1), which makes |θ_e| <= π/4. Unlike the unwrapped form it does not depend on which of the four
//    cross vectors represents a face, and it changes continuously when frames rotate.
//  - Indices are stored in quarters: quarter_index(p) = 4·ind_p ∈ Z. Boundary vertices have index 0.
//    A branch point is a vertex with quarter_index ≠ 0 mod 4 (odd: ±1 mod 4, even: 2 mod 4).
//    With our sign of m the matching index (Def. 3.2) is 4·ind_p(m) = -Σ m over the edges crossed counter-clockwise
//    around p. It agrees with the cross-field index (Def. 3.3) modulo 4 quarters (same branch points, same
//    even/odd class). For the straightest matching (5.1), exactly ind^cross_p = ind_p(m) + ind_p(X), ind_p(X) the
//    integer vector-field index of X itself (Def. 1.18 with zero matching). On a closed surface Σ_p ind^cross_p = χ
//    for any field and matching, while Σ_p ind_p(m) = 0 (each edge is crossed once each way by the loops of its
//    two endpoints): the integer part of a vertex's index is carried by θ, not by the matching.
#include <Eigen/Core>
#include <complex>
#include <utility>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

/// A change of the matching m_e of one edge by `delta` quarter turns (with the edge's orientation): the unit that
/// branch point relocation (field/relocation.h) and Algorithm 6.1 (optimize/) apply.
struct MatchingChange {
  int edge;
  int delta;
};

struct FrameField {
  Eigen::VectorXcd X;        ///< #F: first frame vector, face basis
  Eigen::VectorXcd Y;        ///< #F: second frame vector (= i·X for a cross field)
  Eigen::VectorXi matching;  ///< #E: m_e, 0 on boundary edges
};

struct BranchPoint {
  int vertex;
  /// 4·ind_p, never 0 mod 4. branch_points() (field/indices.h) reports the cross-field index (Def. 3.3), whose
  /// sum is χ; the covering works with the matching index (Def. 3.2). Both agree modulo 4 (see above).
  int quarter_index;
};

/// A cross field (Y = iX) with the given first vectors and matching.
/// \pre none (sizes are #F and #E of the mesh the field is used with).
FrameField make_cross_field(Eigen::VectorXcd X, Eigen::VectorXi matching);

/// First vector of the orthogonalized frame (X,Y)^⊥ = ½(X - JY, JX + Y) (thesis 3.1.2); the second is i times it.
/// \pre none
inline Complex orthogonalized(Complex X, Complex Y) { return 0.5 * (X - Complex(0, 1) * Y); }
/// First vectors of (X_t,Y_t)^⊥ for every face. \return #F \pre none
Eigen::VectorXcd orthogonalized_frames(const FrameField& field);

/// The frame-switching operator of our convention applied k times: R'^k(X, Y) with R'(X,Y) = (Y,-X), i.e. the
/// thesis's R^{-k} (R(X,Y) = (-Y,X), R² = -id (3.1)). For Y = iX it multiplies both vectors by i^k. \pre none
std::pair<Complex, Complex> frame_switch(Complex X, Complex Y, int k);

/// Unit cross directions in 3D for drawing: u_t and v_t = n_t × u_t; the cross at t is {±u_t, ±v_t}.
struct CrossDirections {
  Eigen::MatrixX3d u;  ///< #F by 3, world coordinates of X^⊥_t / |X^⊥_t|
  Eigen::MatrixX3d v;  ///< #F by 3, the quarter turn of u_t about the face normal
};
CrossDirections cross_directions(const Mesh& mesh, const FrameField& field);  ///< \pre field belongs to mesh (X, Y #F).

}  // namespace quadcover
