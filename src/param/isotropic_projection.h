#pragma once
// The positive semidefinite part of the Hessian of a rotation-invariant 2D density (beyond the thesis): the untangling
// density f_ε (param/untangle.h) depends on J only through ‖J‖² and det J. For such a density the Hessian in the
// entries (J00, J01, J10, J11) has the eigenvectors of J's signed SVD J = U diag(s1, s2) Vᵀ: the twist U R Vᵀ / √2 and
// the flip U F Vᵀ / √2 (R = [0 −1; 1 0], F = [0 1; 1 0]), and a 2 × 2 block on U e_k e_kᵀ Vᵀ (Smith, De Goes, Kim,
// "Analytic eigensystems for isotropic distortion energies", 2019). Projecting with them replaces a 4 × 4 eigen
// decomposition by a 2 × 2 one.
#include <Eigen/Core>

namespace quadcover {

/// Σ max(λ_k, 0) e_k e_kᵀ over the eigenpairs of `hessian`, where hessian is the Hessian at J of a density that depends
/// on J only through ‖J‖² and det J (in the entries J00, J01, J10, J11). \pre hessian symmetric, of such a density.
Eigen::Matrix4d project_isotropic_hessian(const Eigen::Matrix2d& J, const Eigen::Matrix4d& hessian);

}  // namespace quadcover
