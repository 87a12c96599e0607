#pragma once
// The harmonic correction of a jump field on the covering (thesis 1.2.5 on M̃, 4.2.1): for the function σ with
// jumps c across the cut, Σ̃_c = ∇σ and H̃_c = Σ̃_c − (Σ̃_c)_P, the projection (Σ̃_c)_P = ∇u onto gradients of
// conforming covering functions: 𝔏̄ u = −div Σ̃_c with branch point rows removed ((1.14) on M̃, (3.8) conforming).
// The factorization of 𝔏̄ is computed once and reused for every right-hand side (the period matrix needs one per
// symmetric path, 6.3.2).
#include <Eigen/SparseCore>
#include <functional>
#include <vector>

#include "calculus/sparse_cholesky.h"
#include "cover/complex_stiffness.h"
#include "param/cover_cut.h"
#include "param/disk_functions.h"

namespace quadcover {

class HarmonicCorrection {
 public:
  /// `trivial` per component of M: true iff its gauged matching has trivial holonomy (then one vertex per such
  /// component is pinned against the constant kernel of 𝔏̄). \throw NumericalError if the factorization fails.
  HarmonicCorrection(const Mesh& mesh, const CoverCut& cut, const std::vector<char>& trivial);

  /// Right-hand side b_p = ⟨∇φ_p, Σ⟩ over the faces around p (read in p's gauge; 0 at branch points). Only the
  /// listed faces contribute (pass all faces, or the support of a sparse Σ). Kernel pins are not zeroed here.
  /// \pre Sigma is #F by 2; faces in [0, #F).
  Eigen::VectorXcd rhs(const FramePairs& Sigma, const std::vector<int>& faces) const;
  Eigen::VectorXcd rhs(const FramePairs& Sigma) const;  ///< \pre Sigma is #F by 2.
  /// The same for a field given only on `faces` (X[k], Y[k] on faces[k]; zero elsewhere): no dense #F field.
  /// \pre X, Y have faces.size() entries; faces in [0, #F).
  Eigen::VectorXcd rhs(const std::vector<int>& faces, const std::vector<Complex>& X,
                       const std::vector<Complex>& Y) const;
  /// u with 𝔏̄ u = b (rows of the kernel pins replaced by u_p = 0), all columns at once.
  /// \pre B has #V rows. \throw NumericalError if the solve fails.
  Eigen::MatrixXcd solve(Eigen::MatrixXcd B) const;
  /// Frees the factor of 𝔏̄, for a caller that solves with its own constraints from here on (param/alignment.h);
  /// solve() and harmonic_part() throw NumericalError afterwards. \pre none
  void release_factor();
  /// Per-corner values i^λ u_p of a vertex function (0 at branch points). \pre u has #V entries.
  Eigen::MatrixX3cd corner_values(const Eigen::VectorXcd& u) const;
  /// H̃ = Σ − ∇u for the u solved from Σ. \pre Sigma is #F by 2. \throw NumericalError if the solve fails.
  FramePairs harmonic_part(const FramePairs& Sigma) const;

  const Eigen::SparseMatrix<Complex>& stiffness() const { return L_; }  ///< 𝔏̄, unpinned \pre none
  const VertexLayers& layers() const { return layers_; }  ///< \pre none
  const std::vector<int>& kernel_pins() const { return kernel_pins_; }  ///< \pre none

 private:
  void add_rhs(int f, Complex X, Complex Y, Eigen::VectorXcd& b) const;  ///< face f's terms of rhs()

  const Mesh* mesh_;
  VertexLayers layers_;
  Eigen::SparseMatrix<Complex> L_;
  std::vector<int> kernel_pins_;
  SparseCholesky<Complex> chol_;
};

/// Solve callbacks of the final correction with the caller's constraints (pins, curves), for the relaxation and the
/// stiffening of param/: u of 𝔏̄ u = b with 𝔏̄ already factored by the caller,
using CorrectionResolve = std::function<Eigen::VectorXcd(const Eigen::VectorXcd& b)>;
/// and u of 𝔏̄_w u = b_w for a weighted matrix; refactorize = false reuses the factor of the previous call (same Lw).
using WeightedCorrectionSolve = std::function<Eigen::VectorXcd(const Eigen::SparseMatrix<Complex>& Lw,
                                                               const Eigen::VectorXcd& bw, bool refactorize)>;

/// Replaces rows and columns of a Hermitian matrix by those of the identity (the values there pinned to 0).
/// \pre A is square; rows in [0, A.rows()).
void pin_rows(Eigen::SparseMatrix<Complex>& A, const std::vector<int>& rows);

/// ‖Z‖² = Σ_f A_f (|X_f|² + |Y_f|²) and the real inner product ⟨Z, W⟩ it comes from. \pre Z is #F by 2.
double frame_norm2(const Mesh& mesh, const FramePairs& Z);
double frame_inner(const Mesh& mesh, const FramePairs& Z, const FramePairs& W);  ///< \pre Z, W are #F by 2.

}  // namespace quadcover
