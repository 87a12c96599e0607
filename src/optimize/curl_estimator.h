#pragma once
// Local estimates of E_D for screening Algorithm 6.1's candidates (beyond the thesis), around the state of a
// CurlEnergy (the exact evaluator, optimize/curl_energy.h).
//
// The re-smoothing is solved on a patch of a few face rings around the changed edges only
// (SmoothingSystem::solve_local), curl* changes only on the patch's edges (a sparse right-hand side), and E_D comes
// from the reach-limited forward solve on the etree paths of the changed rows (FactorTrial::evaluate). The part of
// Δα outside the patch is added to first order with the adjoint z = A⁻¹ ∇_α E_D:
//   E_D(α+Δα) ≈ E_D(α+Δα_P) + zᵀΔb - (∇_α E_D)ᵀΔα_P  (exact when the patch is the whole mesh).
// Algorithm 6.1 screens candidates with estimates and confirms each accepted move with CurlEnergy::evaluate().
#include <memory>
#include <span>
#include <tuple>
#include <vector>

#include "optimize/curl_energy.h"
#include "optimize/local_smoothing.h"

namespace quadcover {

/// Per-thread scratch of CurlEstimator::estimate() (sized on first use; reused without O(n) clears).
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

class CurlEstimator {
 public:
  /// Estimates around `energy`'s current state, re-smoothing with its smoother's matrix (5.4).
  /// \pre energy (and its mesh and smoother) outlive this.
  explicit CurlEstimator(CurlEnergy& energy);
  ~CurlEstimator();

  /// Computes ∇_α E_D and the adjoint z of the energy's current state (one back substitution with 𝔏̄*, one solve
  /// with A); needed after every commit before estimate(). No-op if current or if fewer than
  /// CurlEnergyOptions::estimate_refresh commits happened since the last computation (stale far field).
  /// \throw NumericalError if a solve fails.
  void prepare();
  /// Local estimate of E_D after `changes` (see the file comment). Const and thread-safe with one workspace per
  /// thread; deterministic. \pre prepare() since the last commit. \return +infinity if an update failed.
  double estimate(std::span<const MatchingChange> changes, EstimateWorkspace& ws) const;
  /// The same estimate on a patch of `rings` face rings (estimate() uses CurlEnergyOptions::local_rings).
  /// \pre prepare() since the last commit. \throw std::logic_error otherwise.
  double estimate(std::span<const MatchingChange> changes, EstimateWorkspace& ws, int rings) const;
  /// Estimates of several change sets, in parallel on up to `threads` threads (0 = all cores); the result does
  /// not depend on the thread count. Calls prepare(). \pre out.size() == candidates.size().
  void estimate_batch(std::span<const std::vector<MatchingChange>> candidates, std::span<double> out, int threads = 0);
  /// Timings and sizes of all estimates so far (summed over the workspaces). \pre none
  CurlEnergyTimings timings() const;

 private:
  bool ready() const;
  CurlEnergy* energy_;
  SmoothingSystem system_;
  Eigen::VectorXd grad_, adjoint_;  // ∇_α E_D and z = A⁻¹∇_α E_D of the state at the last full prepare()
  long prepared_commits_ = -1, prepared_rebuilds_ = -1;  // the energy's clock at the last full prepare()
  long ready_commits_ = -1;                              // ... and at the last prepare(), full or stale
  struct Workspaces;
  std::unique_ptr<Workspaces> workspaces_;
};

}  // namespace quadcover
