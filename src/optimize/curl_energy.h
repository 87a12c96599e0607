#pragma once
// Fast re-evaluation of the curl distortion E_D = ½‖X_C‖² = ½xᴴx, L x = -curl*X, 𝔏̄* = LᴴL (thesis 6.1.1, 6.2.1)
// after changes of the matching, with Cholesky up/downdates instead of refactorization.
//
// One evaluation (Table 6.1): the matching changes at some edges; the frame field is re-smoothed by minimizing
// E(α) (5.3) with the new matching (5.2.2, FrameSmoother: two right-hand side entries per edge, one solve); curl*
// of the rotated field is recomputed; 𝔏̄* changes by a four-entry star per edge (Deng split, two rank-1 terms
// applied to private copies of the affected factor columns); one forward solve gives E_D. Nothing is written
// back unless the change is committed.
#include <span>
#include <vector>

#include "field/frame_field.h"
#include "field/smoothing.h"
#include "optimize/updatable_cholesky.h"

namespace quadcover {

struct CurlEnergyOptions {
  /// 𝔏̄* + ε·I with ε = diagonal_shift × mean diagonal: keeps the factor definite when the covering is trivial
  /// (no odd branch points and trivial holonomy: constants are symmetric). Changes E_D by a relative ~ε/λ_min.
  double diagonal_shift = 1e-10;
};

/// A matching change m_e += delta on an interior edge.
struct MatchingChange {
  int edge;
  int delta;
};

/// Seconds spent per stage of evaluate() (accumulated), the columns of Table 6.1.
struct CurlEnergyTimings {
  double smoothing = 0, curl = 0, update = 0, solve = 0, other = 0;
  long evaluations = 0;
};

class CurlEnergy {
 public:
  /// Factors 𝔏̄* of the smoother's current matching and evaluates E_D of the re-smoothed field.
  /// Keeps pointers to mesh and smoother, which must outlive this object; the smoother's matching is changed by
  /// commit() only (evaluate() restores it).
  /// \throw NumericalError if 𝔏̄* cannot be factored.
  CurlEnergy(const Mesh& mesh, FrameSmoother& smoother, const CurlEnergyOptions& options = {});

  /// E_D of the current state.
  double energy() const { return 0.5 * factor_.rhs_energy(); }
  /// E_D after applying `changes` (one edge at a time, in order), without changing the state.
  /// \return +infinity if an update lost positive definiteness (never expected for valid matchings).
  double evaluate(std::span<const MatchingChange> changes);
  /// Makes the last evaluate() the current state.
  void commit();
  /// Recomputes everything from scratch for the current matching (factorization included): the reference the
  /// updates are tested against. \return E_D.
  double recompute_from_scratch();

  const FrameField& field() const { return field_; }
  const Eigen::VectorXi& matching() const { return field_.matching; }
  const Eigen::VectorXd& alpha() const { return alpha_; }
  /// Curvature θ_e of the current (rotated) field: θ⁰_e - α_s + α_t... as seen by E_S (5.3), #E.
  double curvature(int e) const;
  /// Per-edge share of E_D used for sorting (Algorithm 6.1 step 2): |Re(conj(v_e) curl*X(e))|, v = 𝔏̄*⁻¹(-curl*X).
  Eigen::VectorXd distortion_shares() const;
  const UpdatableCholesky& factor() const { return factor_; }
  const CurlEnergyTimings& timings() const { return timings_; }
  void reset_timings() { timings_ = {}; }
  /// The star change of 𝔏̄* (3.8) when m_e changes by delta, given the current layers.
  StarChange stiffness_change(int e, int delta) const;

 private:
  int layer_after(int e, int new_matching) const;
  Eigen::SparseMatrix<Complex> shifted_stiffness() const;
  Eigen::VectorXcd rhs(const Eigen::VectorXd& alpha) const;

  const Mesh* mesh_;
  FrameSmoother* smoother_;
  CurlEnergyOptions options_;
  double shift_ = 0;
  Eigen::MatrixX3i mu_;  // edge layers (cover/complex_stiffness.h) of the current matching
  Eigen::VectorXcd X0_;  // unrotated first frame vectors of the smoother
  Eigen::MatrixX3cd edge_vec_;  // face edge vectors in the face basis
  Eigen::VectorXd alpha_;
  FrameField field_;
  UpdatableCholesky factor_;
  FactorTrial trial_;
  // pending trial
  std::vector<MatchingChange> pending_;
  Eigen::VectorXd pending_alpha_;
  bool pending_valid_ = false;
  CurlEnergyTimings timings_;
};

}  // namespace quadcover
