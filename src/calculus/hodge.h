#pragma once
// Discrete Hodge decomposition X = X_P + X_C + X_H (Theorem 1.12) via (1.8)-(1.10), factorizing 𝔏 and 𝔏* once
// and reusing the factors for every field.
//
// Reference implementation on the real surface M: the product removes curl on the covering (cover/, param/
// parameterize.cpp); tests/param/reference_stack_test.cpp checks that, with a matching ≡ 0, its E_D = ‖X̃_C‖² is the
// ‖X_C‖² of this decomposition.
//
// Kernel (1.10): on every connected component one vertex (and, on closed components, one edge) is pinned to 0,
// which makes the reduced matrices positive definite without any diagonal shift; the solution is then shifted by
// a constant per component so that ∫u dA = 0 (and ∫v dA = 0 on closed components). The result is the exact
// solution of the singular system, not a regularized one.
//
// Boundary conditions (meshes with boundary):
//  - potential u ∈ S_h: natural (Neumann), as (1.8) is written: 𝔏u = -div X at every vertex, boundary included.
//  - co-potential v ∈ S_h*: Dirichlet, v = 0 at the midpoints of boundary edges; (1.9) 𝔏*v = -curl* X holds at
//    every interior edge. With natural conditions on both the parts would not be orthogonal (∇φ_p and J∇ψ_e
//    overlap when e is a boundary edge); with this choice 𝒫 = ∇S_h ⊥ 𝒞 = J∇S_h*,0, X - X_C is the L²-closest
//    field with curl* = 0 on all interior edges (the locally integrable fields), and the harmonic part
//    ker div ∩ ker curl*(interior) has dimension 2g + b - 1 per component (b boundary loops; 2g when closed).
#include <memory>

#include "calculus/sparse_cholesky.h"
#include "calculus/vector_field.h"

namespace quadcover {

struct HodgeOptions {
  /// Factorization library for 𝔏 and 𝔏*; default Automatic (CHOLMOD when built with it, else Eigen).
  CholeskyBackend backend = CholeskyBackend::Automatic;
};

struct HodgeParts {
  VectorField exact;            ///< X_P = ∇u, u ∈ S_h
  VectorField coexact;          ///< X_C = J∇v, v ∈ S_h* (v = 0 on boundary edges)
  VectorField harmonic;         ///< X_H = X - X_P - X_C
  Eigen::VectorXd potential;    ///< u, #V, ∫u dA = 0 per component
  Eigen::VectorXd copotential;  ///< v, #E, ∫v dA = 0 per closed component, 0 on boundary edges
};

class HodgeDecomposer {
 public:
  /// Factorizes the reduced 𝔏 and 𝔏* of the mesh (once). The mesh must outlive the decomposer.
  /// \pre mesh is a valid triangle mesh. \throw NumericalError if a factorization fails.
  explicit HodgeDecomposer(const Mesh& mesh, const HodgeOptions& options = {});
  ~HodgeDecomposer();
  HodgeDecomposer(HodgeDecomposer&&) noexcept;

  /// X: #F. Orthogonal parts summing to X (see the boundary conditions above).
  /// \throw std::invalid_argument if X.size() != #F.
  HodgeParts decompose(const VectorField& X) const;
  /// u with 𝔏u = -div X (1.8), normalized (1.10). \throw std::invalid_argument if X.size() != #F.
  Eigen::VectorXd exact_potential(const VectorField& X) const;
  /// v with 𝔏*v = -curl* X (1.9) on interior edges, v = 0 on boundary edges, normalized (1.10) when closed.
  /// \throw std::invalid_argument if X.size() != #F.
  Eigen::VectorXd coexact_potential(const VectorField& X) const;
  /// Solves 𝔏u = rhs (#V), normalized. rhs is first projected to the range of 𝔏 (its mean per component is
  /// removed), so a right-hand side that sums to zero per component is solved exactly.
  /// \throw std::invalid_argument if rhs.size() != #V.
  Eigen::VectorXd solve_conforming(const Eigen::VectorXd& rhs) const;
  /// Solves 𝔏*v = rhs (#E) on interior edges with v = 0 on boundary edges (rhs there is ignored); on closed
  /// components rhs is projected to the range (mean removed) and v normalized like solve_conforming.
  /// \throw std::invalid_argument if rhs.size() != #E.
  Eigen::VectorXd solve_nonconforming(const Eigen::VectorXd& rhs) const;

  const Mesh& mesh() const;  ///< \pre none

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace quadcover
