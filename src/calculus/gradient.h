#pragma once
// Gradients of Lagrange (conforming) and Crouzeix–Raviart (nonconforming) functions (thesis 1.2):
// ∇φ_p|t = (1/2A_t) J e and ∇ψ_e|t = -(1/A_t) J e, as complex per-face vectors (see vector_field.h).
#include <Eigen/SparseCore>

#include "calculus/vector_field.h"

namespace quadcover {

/// #F by #V complex: (G u)_t = ∇u|_t for u ∈ S_h given at the vertices. \pre none
Eigen::SparseMatrix<Complex> conforming_gradient(const Mesh& mesh);
/// #F by #E complex: (G* v)_t = ∇v|_t for v ∈ S_h* given at the edge midpoints. \pre none
Eigen::SparseMatrix<Complex> nonconforming_gradient(const Mesh& mesh);

/// ∇u per face for u ∈ S_h given at the vertices (u: #V). \throw std::invalid_argument on a size mismatch.
VectorField gradient(const Mesh& mesh, const Eigen::VectorXd& u);
/// ∇v per face for v ∈ S_h* given at the edge midpoints (v: #E). \throw std::invalid_argument on a size mismatch.
VectorField nonconforming_gradient(const Mesh& mesh, const Eigen::VectorXd& v);

}  // namespace quadcover
