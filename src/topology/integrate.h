#pragma once
// Integration of locally integrable (curl*-free) fields over the cut mesh (thesis 1.2.5, (1.11)-(1.12)):
// starting from one corner per piece, u_q = u_p + ⟨e, X_t⟩ across the uncut edges e = (p, q).
//
// Reference implementation: the product integrates on the covering's cut disk (param/disk_functions.h
// integrate_on_disk); tests/param/reference_stack_test.cpp checks that both agree on the same cut mesh with a
// matching ≡ 0.
#include <Eigen/Core>

#include "calculus/vector_field.h"
#include "topology/cut_mesh.h"

namespace quadcover {

/// Potential of X on the cut mesh: one value per cut-vertex (CutMesh::original_vertex indexing) with
/// u(q) - u(p) = ⟨q - p, X_t⟩ (1.12) along a breadth-first spanning tree of each piece, starting from the
/// smallest face of the piece with u = 0 at its corner 0. If curl* X = 0 on the uncut interior edges and every
/// piece is a disk, ∇u = X on every face; otherwise ∇u is the integral along that spanning tree.
/// \throw InputError if X does not have #F entries.
Eigen::VectorXd integrate_cut_vertices(const Mesh& mesh, const CutMesh& cut, const VectorField& X);

/// The same as per-corner values (#F by 3, CornerData): φ(f, k) = u(cut.corner_vertex(f, k)).
/// \throw InputError if X does not have #F entries.
Eigen::MatrixX3d integrate(const Mesh& mesh, const CutMesh& cut, const VectorField& X);

/// φ = φ⁰ + iφ¹ per corner with ∇φ⁰ = X and ∇φ¹ = Y: the parameterization of a frame field (X, Y) that is
/// integrable on the cut mesh (thesis 2.3). \throw InputError if X or Y does not have #F entries.
Eigen::MatrixX3cd integrate_frame(const Mesh& mesh, const CutMesh& cut, const VectorField& X, const VectorField& Y);

}  // namespace quadcover
