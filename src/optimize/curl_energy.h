#pragma once
// Fast re-evaluation of the curl distortion E_D = ½‖X̃_C‖² = xᴴx, L x = -curl*X, 𝔏̄* = LᴴL (thesis 6.1.1, 6.2.1)
// after changes of the matching, with Cholesky up/downdates instead of refactorization. It is the E_D parameterize()
// reports (Parameterization::energy_curl / scale², up to the shift below), with v = 0 on boundary edges (1.2.4) as
// there (tests/optimize/one_energy_test.cpp).
//
// One evaluation (Table 6.1): the matching changes at some edges; the frame field is re-smoothed by minimizing
// E(α) (5.3) with the new matching (5.2.2, FrameSmoother: two right-hand side entries per edge, one solve); curl*
// of the rotated field is recomputed; 𝔏̄* changes by a four-entry star per edge (Deng split, two rank-1 terms
// applied to private copies of the affected factor columns); one forward solve gives E_D. Nothing is written
// back unless the change is committed.
//
// Local estimate (beyond the thesis; estimate()): the re-smoothing is solved on a patch of a few face rings around
// the changed edges only (SmoothingSystem::solve_local), curl* changes only on the patch's edges (a sparse
// right-hand side), and E_D comes from the reach-limited forward solve on the etree paths of the changed rows
// (FactorTrial::evaluate). The part of Δα outside the patch is added to first order with the adjoint
// z = A⁻¹ ∇_α E_D:  E_D(α+Δα) ≈ E_D(α+Δα_P) + zᵀΔb - (∇_α E_D)ᵀΔα_P  (exact when the patch is the whole mesh).
// Algorithm 6.1 screens candidates with estimates and confirms each accepted move with evaluate().
#include <memory>
#include <span>
#include <tuple>
#include <vector>

#include "field/frame_field.h"
#include "field/smoothing.h"
#include "optimize/local_smoothing.h"
#include "optimize/updatable_cholesky.h"

namespace quadcover {

struct CurlEnergyOptions {
  /// 𝔏̄* + ε·I with ε = diagonal_shift × mean diagonal: keeps the factor definite when the covering is trivial
  /// (no odd branch points and trivial holonomy: constants are symmetric). Changes E_D by a relative ~ε/λ_min.
  double diagonal_shift = 1e-10;
  /// estimate(): face rings of the local re-smoothing patch around the changed edges, and its CG tolerance.
  int local_rings = 6;
  double local_tolerance = 1e-8;
  /// estimate(): ∇_α E_D and the adjoint z of the far-field correction are recomputed (one back substitution
  /// with 𝔏̄*, one solve with A) after this many commits, not after every one (1 = always current). Affects the
  /// screening only: every accepted move is still confirmed exactly.
  int estimate_refresh = 8;
};

/// Seconds spent per stage of evaluate() (accumulated), the columns of Table 6.1.
struct CurlEnergyTimings {
  double smoothing = 0, curl = 0, update = 0, solve = 0, other = 0;
  long evaluations = 0;
  /// Outside evaluate(): prepare_estimates() (back solve, ∇_α E_D, adjoint solve), distortion_shares() (back
  /// solve), commit() (writing the trial back). Wall seconds, accumulated.
  double prepare = 0, shares = 0, commit = 0;
  long prepares = 0;
};

/// Per-thread scratch of CurlEnergy::estimate() (sized on first use; reused without O(n) clears).
struct EstimateWorkspace {
  FactorTrial trial;
  LocalSmoothingWork smoothing;
  std::vector<FaceEntry> db_smooth;                    // Δb of (5.4)
  std::vector<std::pair<int, int>> m_override;         // (edge, new m_e)
  std::vector<std::pair<int, double>> theta_override;  // (edge, new θ_e)
  std::vector<std::tuple<int, int, int>> mu_override;  // (face, slot, new μ)
  std::vector<int> face_stamp, edge_stamp, edge_slot;
  int stamp = 0;
  std::vector<SparseEntry> db_curl;  // Δ(-curl*X) on the patch edges
  CurlEnergyTimings timings;         // smoothing / curl / update / solve of the estimates made with this workspace
  long patch_faces = 0, reach_columns = 0;  // summed over the estimates
};

class CurlEnergy {
 public:
  /// Factors 𝔏̄* of the smoother's current matching and evaluates E_D of the re-smoothed field.
  /// Keeps pointers to mesh and smoother, which must outlive this object; the smoother's matching is changed by
  /// commit() only (evaluate() restores it).
  /// The estimates re-smooth with the smoother's own matrix (5.4) (SmoothingSystem).
  /// \throw NumericalError if 𝔏̄* cannot be factored.
  CurlEnergy(const Mesh& mesh, FrameSmoother& smoother, const CurlEnergyOptions& options = {});
  ~CurlEnergy();
  CurlEnergy(CurlEnergy&&) noexcept;

  /// E_D of the current state. \pre none
  double energy() const { return factor_.rhs_energy(); }
  /// E_D after applying `changes` (one edge at a time, in order), without changing the state.
  /// \return +infinity if an update lost positive definiteness (never expected for valid matchings).
  /// \pre every change names an edge of the mesh (boundary edges and delta 0 are skipped). \throw NumericalError if the smoothing solve fails.
  double evaluate(std::span<const MatchingChange> changes);
  /// Computes ∇_α E_D and the adjoint z of the current state (one back substitution with 𝔏̄*, one solve with A);
  /// needed after every commit before estimate(ws). No-op if current or if fewer than
  /// CurlEnergyOptions::estimate_refresh commits happened since the last computation (stale far field).
  /// \throw NumericalError if a solve fails.
  void prepare_estimates();
  /// Local estimate of E_D after `changes` (see the file comment). Const and thread-safe with one workspace per
  /// thread; deterministic. \pre prepare_estimates() since the last commit. \return +infinity if an update failed.
  double estimate(std::span<const MatchingChange> changes, EstimateWorkspace& ws) const;
  /// The same estimate on a patch of `rings` face rings (estimate() uses CurlEnergyOptions::local_rings).
  /// \pre prepare_estimates() since the last commit. \throw std::logic_error otherwise.
  double estimate(std::span<const MatchingChange> changes, EstimateWorkspace& ws, int rings) const;
  const CurlEnergyOptions& options() const { return options_; }  ///< \pre none
  /// Estimates of several change sets, in parallel on up to `threads` threads (0 = all cores); the result does
  /// not depend on the thread count. Calls prepare_estimates().
  /// \pre out.size() == candidates.size().
  void estimate_batch(std::span<const std::vector<MatchingChange>> candidates, std::span<double> out, int threads = 0);
  /// Timings and sizes of all estimates so far (summed over the workspaces). \pre none
  CurlEnergyTimings estimate_timings() const;
  /// Makes the last evaluate() the current state.
  /// \throw NumericalError if the last evaluate() failed or there was none since the last commit.
  void commit();
  /// Recomputes everything from scratch for the current matching (factorization included): the reference the
  /// updates are tested against. \return E_D. \throw NumericalError if 𝔏̄* cannot be factored.
  double recompute_from_scratch();

  const FrameField& field() const { return field_; }  ///< \pre none
  const Eigen::VectorXi& matching() const { return field_.matching; }  ///< \pre none
  const Eigen::VectorXd& alpha() const { return alpha_; }  ///< \pre none
  /// Curvature θ_e of the current (rotated) field: θ⁰_e - α_s + α_t... as seen by E_S (5.3), #E. \pre 0 <= e < #E
  double curvature(int e) const;
  /// Per-edge share of E_D used for sorting (Algorithm 6.1 step 2): |Re(conj(v_e) curl*X(e))|, v = 𝔏̄*⁻¹(-curl*X).
  /// \pre none
  Eigen::VectorXd distortion_shares() const;
  const UpdatableCholesky& factor() const { return factor_; }  ///< \pre none
  const CurlEnergyTimings& timings() const { return timings_; }  ///< \pre none
  void reset_timings() { timings_ = {}; }  ///< \pre none
  /// The star change of 𝔏̄* (3.8) when m_e changes by delta, given the current layers. \pre e is an interior edge.
  StarChange stiffness_change(int e, int delta) const;

 private:
  int layer_after(int e, int new_matching) const;
  template <class Layer>
  StarChange star_change(int e, int new_matching, Layer mu) const;
  Complex contribution(int f, int k, double alpha, int mu) const;
  Complex term(int f, int k, Complex rotated, int mu) const;
  SmoothingSystem system_;
  Eigen::VectorXd grad_, adjoint_;  // ∇_α E_D and z = A⁻¹∇_α E_D of the current state (prepare_estimates)
  bool estimates_ready_ = false;
  int commits_since_prepare_ = 0;
  mutable Eigen::VectorXcd solution_;  // v = 𝔏̄*⁻¹(-curl*X) of the current state, when solution_valid_
  mutable bool solution_valid_ = false;
  const Eigen::VectorXcd& solution() const;
  struct Workspaces;
  std::unique_ptr<Workspaces> workspaces_;
  Eigen::SparseMatrix<Complex> shifted_stiffness() const;
  Eigen::VectorXcd rhs(const Eigen::VectorXd& alpha) const;

  const Mesh* mesh_;
  FrameSmoother* smoother_;
  CurlEnergyOptions options_;
  double shift_ = 0;
  Eigen::MatrixX3i mu_;         // edge layers (cover/complex_stiffness.h) of the current matching
  Eigen::VectorXcd X0_;         // unrotated first frame vectors of the smoother
  Eigen::MatrixX3cd edge_vec_;  // face edge vectors in the face basis
  Eigen::VectorXd alpha_;
  FrameField field_;
  UpdatableCholesky factor_;
  FactorTrial trial_;
  // pending trial
  std::vector<MatchingChange> pending_;
  Eigen::VectorXd pending_alpha_;
  bool pending_valid_ = false;
  mutable CurlEnergyTimings timings_;  // distortion_shares() is const but timed
};

}  // namespace quadcover
