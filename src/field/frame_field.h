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
//  - Curvature (3.4): θ_e = arg(X_t / (i^{m_e} ρ_e X_s)) ∈ (-π, π]; the initial matching (5.1) makes |θ_e| <= π/4.
//  - Indices are stored in quarters: quarter_index(p) = 4·ind_p ∈ Z. Boundary vertices have index 0.
//    A branch point is a vertex with quarter_index ≠ 0 mod 4 (odd: ±1 mod 4, even: 2 mod 4).
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

struct FrameField {
  Eigen::VectorXcd X;        ///< #F: first frame vector, face basis
  Eigen::VectorXcd Y;        ///< #F: second frame vector (= i·X for a cross field)
  Eigen::VectorXi matching;  ///< #E: m_e, 0 on boundary edges
};

struct BranchPoint {
  int vertex;
  int quarter_index;  ///< 4·ind_p (Def. 3.2), never 0 mod 4
};

}  // namespace quadcover
