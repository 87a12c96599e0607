#pragma once
// Harmonic fields from homology generators (thesis 1.2.6): the cut fields Σ_k (1.13), the standard basis
// H_k = Σ_k - (Σ_k)_P of the harmonic fields, and the harmonic field H_b with prescribed periods (1.14).
//
// Reference implementation on the real surface M: the product computes harmonic fields and periods on the covering
// (param/harmonic_correction.h, param/period_matrix.h); tests/param/reference_stack_test.cpp checks, with a matching
// ≡ 0 on closed surfaces, that the cover's period matrix and the Gram matrix of this basis are congruent (equal
// determinants).
#include <Eigen/SparseCore>
#include <span>

#include "calculus/hodge.h"
#include "topology/homology.h"

namespace quadcover {

/// Σ_k of (1.13) for every generator, as the columns of a sparse #F by n complex matrix: on the faces left of γ_k,
/// Σ_k(t) = Σ_{p ∈ t ∩ γ_k} ∇φ_p(t) (summed over the visits of γ_k at p), zero elsewhere. Σ_k is the gradient of
/// the function that is 1 on the left bank of γ_k and 0 elsewhere, so curl* Σ_k = 0 on every interior edge and
/// b_j(Σ_k) = δ_jk. \throw TopologyError if a generator cannot be walked; InputError for a walk without edges.
Eigen::SparseMatrix<Complex> sigma_fields(const Mesh& mesh, const HomologyBasis& basis);

/// Σ of (1.13) for one edge walk v_0 … v_m (consecutive vertices adjacent): closed (v_m = v_0), or open from a
/// boundary vertex to a boundary vertex. Visits are summed, so Σ(γ) + Σ(γ reversed) = ∇(visit count per vertex).
/// \throw InputError for a walk without edges or a closed walk that does not close; TopologyError if the walk
/// steps between non-adjacent vertices or ends at an interior vertex.
Eigen::SparseVector<Complex> walk_sigma_field(const Mesh& mesh, std::span<const int> vertices, bool closed);

/// Σ_b = Σ_k b_k Σ_k (dense #F). \throw InputError if b.size() != sigma.cols().
VectorField sigma_field(const Eigen::SparseMatrix<Complex>& sigma, const Eigen::VectorXd& b);

/// The standard basis H_k = Σ_k - ∇u_k, 𝔏u_k = -div Σ_k (thesis 1.2.6), one factorization of 𝔏 for all k.
/// H_k is divergence free and curl* free (harmonic) with b_j(H_k) = δ_jk.
/// \pre hodge was built on the same mesh as basis.
std::vector<VectorField> harmonic_basis(const HodgeDecomposer& hodge, const HomologyBasis& basis,
                                        const Eigen::SparseMatrix<Complex>& sigma);

/// H_b = Σ_b - ∇u with 𝔏u = -div Σ_b (1.14): the harmonic field with periods b_j(H_b) = b_j.
/// b  #generators. \throw InputError if b has the wrong size.
VectorField harmonic_field_with_periods(const HodgeDecomposer& hodge, const HomologyBasis& basis,
                                        const Eigen::SparseMatrix<Complex>& sigma, const Eigen::VectorXd& b);

}  // namespace quadcover
