#pragma once
// Stiffness matrices and the edge-vertex incidence (thesis 1.2.1).
#include <Eigen/SparseCore>

#include "mesh/mesh.h"

namespace quadcover {

/// Incidence C of the edge graph, stored #E by #V: C(e,p) = 1 iff p is an endpoint of e (the thesis writes the
/// v×e transpose), so that 𝔏 = ¼ Cᵀ 𝔏* C. \pre none
Eigen::SparseMatrix<double> edge_vertex_incidence(const Mesh& mesh);

/// Conforming (cotan) stiffness 𝔏, #V by #V: 𝔏_pq = -½(cot α_pq + cot β_pq), 𝔏_pp = -Σ_q 𝔏_pq.
/// Symmetric positive semi-definite; kernel = constants per component. \pre none
Eigen::SparseMatrix<double> conforming_stiffness(const Mesh& mesh);

/// Nonconforming Crouzeix–Raviart stiffness 𝔏* (1.5), #E by #E: 𝔏*_ef = -2 cot ∠(e,f) for edges e ~ f of a
/// common triangle, 𝔏*_ee = -Σ_g 𝔏*_eg. Symmetric positive semi-definite; kernel = constants per component. \pre none
Eigen::SparseMatrix<double> nonconforming_stiffness(const Mesh& mesh);

/// Lumped (barycentric) vertex areas, #V: a third of the incident face areas; used for normalization (1.10). \pre none
Eigen::VectorXd vertex_areas(const Mesh& mesh);
/// Edge areas A_e = ⅓(A_s + A_t), #E (thesis 5.2); the integral of a Crouzeix–Raviart basis function. \pre none
Eigen::VectorXd edge_areas(const Mesh& mesh);

}  // namespace quadcover
