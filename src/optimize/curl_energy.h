#pragma once
// Fast re-evaluation of the curl distortion E_D = ½‖X̃_C‖² = xᴴx, L x = -curl*X, 𝔏̄* = LᴴL (thesis 6.1.1, 6.2.1)
// after changes of the matching, with Cholesky up/downdates instead of refactorization. It is the E_D parameterize()
// reports (Parameterization::energy_curl / scale², up to the shift below), with v = 0 on boundary edges (1.2.4) as
// there (tests/optimize/one_energy_test.cpp).
//
// One evaluation (Table 6.1): the matching changes at some edges; the frame field is re-smoothed by minimizing
// E(α) (5.3) with the new matching (5.2.2, FrameSmoother::solve_after: two right-hand side entries per edge, a solve
// from those entries); curl* of the rotated field is recomputed; 𝔏̄* changes by a four-entry star per edge (Deng
// split, two rank-1 terms applied to private copies of the affected factor columns); one forward solve gives E_D.
// Nothing is written back unless the change is committed.
//
// Local estimates of E_D for screening candidates: optimize/curl_estimator.h.
#include <span>
#include <utility>
#include <vector>

#include "common/quarter_turn.h"
#include "field/frame_field.h"
#include "field/smoothing.h"
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
  /// Outside evaluate(): CurlEstimator::prepare() (back solve, ∇_α E_D, adjoint solve), distortion_shares() (back
  /// solve), commit() (writing the trial back). Wall seconds, accumulated.
  double prepare = 0, shares = 0, commit = 0;
  long prepares = 0;
};

class CurlEnergy {
 public:
  /// Factors 𝔏̄* of the smoother's current matching and evaluates E_D of the re-smoothed field.
  /// Keeps pointers to mesh and smoother, which must outlive this object; the smoother's matching is changed by
  /// commit() only (evaluate() restores it).
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
  const CurlEnergyOptions& options() const { return options_; }  ///< \pre none
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
  /// The face whose layer of interior edge e a matching change moves (the non-reference face, the larger index of
  /// EF(e)), and e's slot in it: FE()(face, slot) == e.
  std::pair<int, int> changed_slot(int e) const {
    const int side = mesh_->EF()(e, 0) > mesh_->EF()(e, 1) ? 0 : 1;
    return {mesh_->EF()(e, side), mesh_->EF_corner()(e, side)};
  }
  template <class Layer>
  StarChange star_change(int e, int new_matching, Layer mu) const;
  Complex contribution(int f, int k, double alpha, int mu) const;
  /// Face f's frame turned by α: e^{iα}X⁰_f.
  Complex rotated_frame(int f, double alpha) const { return product(std::polar(1.0, alpha), X0_[f]); }
  Complex term(int f, int k, Complex rotated, int mu) const;
  friend class CurlEstimator;  // reads the state below to estimate around it (optimize/curl_estimator.h)
  long commits_ = 0, rebuilds_ = 0;  // commit() and recompute_from_scratch() calls: the estimator's clock
  mutable Eigen::VectorXcd solution_;  // v = 𝔏̄*⁻¹(-curl*X) of the current state, when solution_valid_
  mutable bool solution_valid_ = false;
  const Eigen::VectorXcd& solution() const;
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

/// Orders the pattern of CurlEnergy's factor ahead of it (UpdatableCholesky::order_ahead): the pattern depends on the
/// mesh only, not on the field, so this may run beside the field stage. \return the ordering the factor of every
/// CurlEnergy on this mesh will have (its perm()), or empty (small meshes, no CHOLMOD). \pre none
std::vector<int> order_curl_energy_ahead(const Mesh& mesh);

// A template: CurlEstimator calls it with its own layer lookup.
template <class Layer>
StarChange CurlEnergy::star_change(int e, int new_matching, Layer mu) const {
  StarChange c;
  c.k = e;
  const auto [g, a] = changed_slot(e);
  const int mu_new = layer_after(e, new_matching);
  const double area = mesh_->face_areas()[g];
  for (int b = 0; b < 3; ++b) {
    if (b == a || mesh_->is_boundary_edge(mesh_->FE()(g, b))) continue;  // pinned rows do not couple
    // 𝔏̄*(e, e_b) from face g = K_ab i^{μ_b - μ_a} (3.8), K_ab = ⟨e_a, e_b⟩ / A_g (1.5).
    const double K = std::real(std::conj(mesh_->edge_vector_local(g, a)) * mesh_->edge_vector_local(g, b)) / area;
    c.d.push_back({mesh_->FE()(g, b), K * (ipow(mu(g, b) - mu_new) - ipow(mu(g, b) - mu(g, a)))});
  }
  return c;
}

}  // namespace quadcover
