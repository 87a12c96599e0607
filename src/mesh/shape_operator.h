#pragma once
// Discrete shape operators of Hildebrandt and Polthier [HP04] (thesis 1.1): an edge-based operator S(e) and the
// vertex operator obtained by summing projected edge operators. Both are *integrated* quantities (curvature ×
// area); divide by the area they are spread over to get pointwise curvature.
//
// Sign convention: the signed turning angle β_e across an interior edge is positive where the surface is convex
// with respect to the outward normal (a sphere with outward normals has β_e > 0), so a principal curvature is
// positive where the surface bends away from its normal (sphere of radius r: κ = 1/r).
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

/// Signed turning angle β_e = π - α_e between the normals of EF(e,0) and EF(e,1) (α_e the interior dihedral
/// angle), positive on convex edges, in (-π, π]. 0 on boundary edges.
/// \return #E \pre none
Eigen::VectorXd signed_dihedral_angles(const Mesh& mesh);

/// Edge shape operator S(e) = 2‖e‖ cos(α_e/2) · u uᵀ, u = unit(ê × n_e), n_e the unit bisector of the two face
/// normals (thesis 1.1; 2‖e‖cos(α_e/2) = 2‖e‖ sin(β_e/2) carries the sign of β_e). Zero on boundary edges.
/// Its one non-zero eigenvalue ≈ ‖e‖β_e is the integrated normal curvature across e, eigenvector ⟂ e and ⟂ n_e.
/// \pre 0 <= e < #E
Eigen::Matrix3d edge_shape_operator(const Mesh& mesh, int e);

/// Vertex shape operators [HP04]: S(p) = ½ Σ_{e∋p} ⟨n_p, n_e⟩ · P_p S(e) P_p, P_p = I - n_p n_pᵀ the projection
/// to the tangent plane of the area-weighted vertex normal n_p. Integrated over the vertex area (⅓ of the incident face
/// areas). \return #V symmetric 3×3 matrices with n_p in their kernel. \pre none
std::vector<Eigen::Matrix3d> vertex_shape_operators(const Mesh& mesh);

/// Area-weighted unit vertex normals. \return #V by 3 \pre none
Eigen::MatrixX3d vertex_normals(const Mesh& mesh);

}  // namespace quadcover
