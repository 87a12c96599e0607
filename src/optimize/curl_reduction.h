#pragma once
// Curl reduction, Algorithm 6.1 (thesis 6.2.2): cancellation of misplaced branch point pairs, edges sorted by their
// share of E_D, greedy matching changes m_e <- m_e - sign(θ_e) kept when E_D decreases (re-sorting after 1‰ of
// the matchings changed), with or without creation of new branch points, and balancing (6.4): cancel pairs whose
// E_D increase Δ_ED is below the expected continuity gain Δ_EH, then reduce again without creation.
#include <string>
#include <vector>

#include "common/progress.h"
#include "optimize/curl_energy.h"
#include "optimize/curl_estimator.h"

namespace quadcover {

struct CurlReductionOptions {
  /// Allow matching changes that create new branch point pairs in the first curl reduction (6.2.2: "very
  /// important"); after a balancing round creation is always disallowed.
  bool allow_creation = true;
  /// k: nearest opposite-index branch points tried per branch point in cancellation and balancing (thesis: 3).
  int cancellation_neighbours = 3;
  /// Re-sort the edges once more than this fraction of the matchings changed in a reduction loop (thesis: 1‰).
  double resort_fraction = 1e-3;
  /// Δ_EH = E_H / (2 h_sym) (6.4), the expected continuity distortion per pair of rounding constraints. Balancing
  /// runs only when it is > 0.
  double delta_eh = 0;
  /// Balancing limits (0 = unlimited): rounds of step 4, and cancellations per round (1 = only the cheapest pair;
  /// used by the Figure 6.5 sweep, optimize/balancing_sweep.h).
  int max_balancing_rounds = 0;
  long max_cancellations_per_round = 0;
  /// Stop after this many E_D evaluations (0 = unlimited) or seconds (0 = unlimited), with the best state so far.
  long max_evaluations = 0;
  double time_limit_seconds = 0;
  /// Screen candidates with CurlEstimator::estimate() (local re-smoothing, reach-limited solve) and evaluate exactly
  /// only the promising ones before accepting. Off: every candidate is evaluated exactly (thesis). Either way E_D
  /// never increases over accepted moves.
  bool local_estimates = true;
  /// A cancellation path (Step 1) is evaluated exactly when its estimate is below E_D·(1 + path_screening_margin):
  /// paths move several edges and their estimates err more (on eight_genus2 an improving cancellation of -1.6%
  /// of E_D is estimated above E_D; 3% catches it). Single-edge moves are screened against E_D itself.
  double path_screening_margin = 0.03;
  /// Threads for screening batches (0 = all cores); results do not depend on it.
  int threads = 0;
  /// Skip reduction moves that leave a triangle with a branch point at each corner (beyond the thesis): the
  /// parameterization puts all three on integer points (4.2.2), which can flip that triangle beyond repair.
  bool separate_branch_points = true;
};

/// One line of the per-iteration log (enough for Figure 6.1 and 6.5).
struct CurlReductionLogEntry {
  long evaluation = 0;  ///< evaluations so far
  double energy = 0;    ///< E_D after this iteration
  int branch_points = 0;
  long accepted = 0;  ///< accepted changes so far
  std::string phase;  ///< "start", "cancellation", "reduction", "balancing"
};

struct CurlReductionResult {
  double initial_energy = 0, final_energy = 0;
  int initial_branch_points = 0, final_branch_points = 0;
  long evaluations = 0, accepted = 0, cancelled_pairs = 0;
  long exact_evaluations = 0;    ///< full re-smoothed evaluations confirming screened candidates (with estimates)
  int balancing_rounds = 0;
  double seconds = 0;
  bool stopped_early = false;  ///< by max_evaluations, time_limit_seconds or progress.cancelled()
  /// "converged" (a whole pass accepted nothing), else what stopped it: "evaluations", "time" or "cancelled".
  std::string stopped_by = "converged";
  std::vector<CurlReductionLogEntry> log;  ///< one entry per accepted change plus phase boundaries
};

/// Runs Algorithm 6.1 on the state of `energy` (its matching and re-smoothed field are updated in place).
/// E_D never increases except in balancing cancellations, each of which costs less than Δ_EH. With
/// options.local_estimates, candidates are screened by `screening` (an estimator of `energy` kept across calls),
/// or by one made for this call when it is null.
/// \pre energy was built on mesh. \throw NumericalError if a commit or refactorization fails.
CurlReductionResult reduce_curl(const Mesh& mesh, CurlEnergy& energy, const CurlReductionOptions& options = {},
                                ProgressSink& progress = null_progress(), CurlEstimator* screening = nullptr);

/// 4·ind_p of the matching (Def. 3.2, field/indices.h) changes by +δ at E(e,0) and -δ at E(e,1) when m_e += δ.
/// Branch points: interior vertices with quarter index ≠ 0 mod 4. \pre quarter_index has #V entries.
int count_branch_points(const Mesh& mesh, const Eigen::VectorXi& quarter_index);

}  // namespace quadcover
