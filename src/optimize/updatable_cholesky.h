#pragma once
// Sparse complex Cholesky factorization 𝔏̄* = LᴴL (thesis 6.2.1) whose factor is modified in place by rank-1
// updates and downdates instead of being recomputed; the sparsity pattern never changes.
//
// Notation: A is n by n Hermitian positive definite (full storage). CXSparse factors P A Pᵀ = L Lᴴ with a fill
// reducing permutation P (AMD); "x" below is the forward-solve vector L x = P b, so that
// bᴴ A⁻¹ b = xᴴx (the identity behind E_D = ½xᴴx, 6.2.1). All indices in this API are in A's original numbering.
#include <Eigen/SparseCore>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "calculus/column_substitution.h"
#include "mesh/mesh.h"

namespace quadcover {

/// One entry of a sparse complex vector, index in A's numbering.
struct SparseEntry {
  int index;
  Complex value;
};

/// A Hermitian change D of A concentrated in row/column k: D(k,j) = d_j, D(j,k) = conj(d_j) for the listed j ≠ k,
/// D(k,k) = 0. A matching change at edge e_k is such a change with two entries (6.2.1, "Sparse Cholesky updates").
struct StarChange {
  int k = -1;
  std::vector<SparseEntry> d;
};

/// The two rank-1 terms of a star change (Deng's eigen-split, 6.2.1): D = w₁w₁ᴴ - w₂w₂ᴴ with
/// w₁,₂ = sqrt(λ/2)·(e_k ± u), λ = sqrt(Σ|d_j|²), u_j = conj(d_j)/λ; eigenvalues ±λ with eigenvectors (e_k ± u)/√2.
/// Applying w₁ (update, λ > 0) before w₂ (downdate) keeps every intermediate matrix positive definite.
/// \return {w₁, w₂}; both empty if D = 0. \pre none
std::pair<std::vector<SparseEntry>, std::vector<SparseEntry>> deng_split(const StarChange& change);

/// Cholesky factor with in-place rank-1 modifications, plus a maintained right-hand side b and forward solution x
/// (L x = P b) so that bᴴA⁻¹b is available after every change without a back substitution.
class UpdatableCholesky {
 public:
  UpdatableCholesky();
  ~UpdatableCholesky();
  UpdatableCholesky(UpdatableCholesky&&) noexcept;
  UpdatableCholesky& operator=(UpdatableCholesky&&) noexcept;

  /// Symbolic analysis (AMD on A) with CXSparse, numeric factorization with CXSparse or, when the factor has large
  /// fronts, CHOLMOD's supernodal one on the same ordering and pattern; sets b = 0.
  /// \throw NumericalError("cholesky") if A is not positive definite or not square.
  /// `route`: Automatic (by the front sizes, as above), UpLooking (always CXSparse) or Supernodal (CHOLMOD when
  /// compiled in).
  enum class Route { Automatic, UpLooking, Supernodal };
  /// \pre A is Hermitian (full storage). A is taken by value: pass a temporary (or std::move) to spare a copy.
  explicit UpdatableCholesky(Eigen::SparseMatrix<Complex> A, Route route = Route::Automatic);
  /// Makes the ordering the factor of a matrix of A's pattern will use, ahead of it (kept with the pattern,
  /// calculus/sparse_cholesky.h: the factor then finds it made). Same factor either way.
  /// \return the ordering as perm() will give it, or empty where CXSparse's AMD orders instead. \pre A square.
  static std::vector<int> order_ahead(const Eigen::SparseMatrix<Complex>& A);
  /// Whether the numbers came from CHOLMOD's supernodal factorization. \pre none
  bool supernodal() const;

  int size() const;  ///< \pre none
  /// Nonzeros of L (including the diagonal). \pre none
  long factor_nonzeros() const;

  /// Sets the right-hand side and recomputes x with a full forward solve. \throw NumericalError if b.size() != size().
  void set_rhs(const Eigen::VectorXcd& b);
  const Eigen::VectorXcd& rhs() const { return b_; }  ///< \pre none
  /// bᴴ A⁻¹ b = xᴴx for the current A and b. \pre none
  double rhs_energy() const { return x_norm2_; }
  /// x in the permuted order (L x = P b). \pre none
  const Eigen::VectorXcd& forward_solution() const { return x_; }
  /// A⁻¹ b (forward and back substitution), in A's numbering. \pre none
  Eigen::VectorXcd solve_full() const;

  /// L L^H <- L L^H + sigma w w^H (sigma = ±1) with CXSparse's cs_ci_updown, then a full forward solve.
  /// The pattern of w w^H must lie in the pattern of A. \throw NumericalError if the result is not positive definite
  /// (the factor is then invalid: refactor).
  void rank1_cxsparse(std::span<const SparseEntry> w, int sigma);
  /// A <- A + D via the two rank-1 terms of deng_split() with cs_ci_updown, then a full forward solve.
  /// \pre as rank1_cxsparse. \throw NumericalError as rank1_cxsparse.
  void apply_star_change_cxsparse(const StarChange& change);

  /// Permutation: perm()[new] = old; etree parent in the permuted numbering (-1 for roots). \pre none
  const std::vector<int>& perm() const { return perm_; }
  const std::vector<int>& inverse_perm() const { return pinv_; }  ///< \pre none
  const std::vector<int>& etree() const { return parent_; }  ///< \pre none
  /// L in the permuted numbering (n by n lower triangular, real positive diagonal). \pre none
  Eigen::SparseMatrix<Complex> factor() const;

  // Raw column storage of L for the path-local evaluator (diagonal first in every column, rows increasing).
  const int* col_ptr() const;  ///< \pre none
  const int* row_idx() const;  ///< \pre none
  Complex* values();  ///< \pre none (writes must keep L a valid factor).
  const Complex* values() const;  ///< \pre none
  /// The split of L's elimination tree for substitutions on two cores (calculus/column_substitution.h; made with the
  /// factor, the pattern never changes); empty below kSplitSubstitutionMinColumns. \pre none
  const SubstitutionSplit& substitution_split() const { return split_; }

 private:
  friend class FactorTrial;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<int> perm_, pinv_, parent_;
  LowerColumns<Complex> columns_;  // L's columns for the split forward solve (its pattern never changes); else empty
  SubstitutionSplit split_;
  Eigen::VectorXcd b_;  // permuted: b_[new] = b[perm[new]]
  Eigen::VectorXcd x_;  // permuted forward solution
  double x_norm2_ = 0;
  void full_forward_solve();
};

/// A tentative modification of an UpdatableCholesky evaluated without touching it ("reach-limited"): star changes
/// and right-hand side changes are applied to private copies of the affected columns only, which all lie on the
/// etree paths from the changed rows to the root; x changes only on those paths, so the new xᴴx costs
/// O(Σ_path nnz(L_j)) instead of a full forward solve. Several trials may evaluate concurrently against the same
/// (unchanged) factor; commit() writes one back.
class FactorTrial {
 public:
  explicit FactorTrial(int n = 0);  ///< \pre n >= 0
  /// Starts a new trial (forgets previous changes; O(touched)). \pre none
  void reset();
  /// Adds A <- A + D (Deng split, update before downdate, 6.2.1). Changes are applied in the order given.
  /// \return false if an intermediate matrix lost positive definiteness (the trial is then invalid).
  /// \pre F.size() is this trial's n; the pattern of D lies in that of A.
  bool add_star_change(const UpdatableCholesky& F, const StarChange& change);
  /// Adds b <- b + delta at entries (A's numbering). \pre F.size() is this trial's n; entries in [0, n).
  void add_rhs_change(const UpdatableCholesky& F, std::span<const SparseEntry> delta);
  /// Reach-limited forward solve on the touched paths. \return the new bᴴA⁻¹b = xᴴx.
  /// \throw NumericalError if an add_star_change failed.
  double evaluate(const UpdatableCholesky& F);
  /// Full forward solve L̃x = P b_new through the modified factor (touched columns read from the trial): for a
  /// right-hand side that changes everywhere (re-smoothed field, 6.2.1 / Table 6.1). \return the new xᴴx.
  /// \pre b_new has F.size() entries. \throw NumericalError if an add_star_change failed.
  double evaluate_full(const UpdatableCholesky& F, const Eigen::VectorXcd& b_new);
  /// Writes the modified columns, b and x back into F (after evaluate() or evaluate_full()).
  /// \pre F is the factor the trial was built on. \throw NumericalError if not evaluated or invalid.
  void commit(UpdatableCholesky& F) const;
  /// Number of columns of L touched (the reach of the change). \pre none
  int reach() const { return static_cast<int>(touched_.size()); }

 private:
  void touch_path(const UpdatableCholesky& F, int j);
  bool rank1(const UpdatableCholesky& F, const std::vector<SparseEntry>& w, double sigma);
  std::vector<int> slot_;                     // column -> offset into vals_, -1 if untouched
  std::vector<int> touched_;                  // touched columns (permuted numbering)
  std::vector<Complex> vals_;                 // private copies of the touched columns
  std::vector<Complex> w_, acc_, db_, xnew_;  // dense work arrays (zero outside touched)
  Eigen::VectorXcd xfull_, bfull_;            // evaluate_full(): permuted b and x
  double energy_ = 0;
  bool valid_ = true, evaluated_ = false, full_ = false;
};

}  // namespace quadcover
