#pragma once
// Figure 6.5 (thesis 6.4): curl distortion E_D, continuity distortion E_H and their sum over the number of branch
// points. Starting from Algorithm 6.1's curl reduction with creation (many branch points), the cheapest pair (by
// Δ_ED) is cancelled and curl reduction without creation re-positions the rest, one pair at a time; at every state
// the field is parameterized (param/parameterize.h) to measure E_H.
#include <vector>

#include "common/progress.h"
#include "field/compute_frame_field.h"
#include "optimize/optimize_field.h"

namespace quadcover {

struct BalancingSweepRow {
  int branch_points = 0;
  double energy_curl = 0;      ///< E_D of the optimized field (6.1.1)
  double energy_harmonic = 0;  ///< E_H of its parameterization (6.1.2)
  double total = 0;            ///< E_D + E_H
  int h_sym = 0;               ///< rounded symmetric periods of that parameterization (4.1)
  long evaluations = 0;        ///< E_D evaluations (screened) spent to reach this state, cumulative
};

struct BalancingSweepOptions {
  OptimizeOptions optimize;   ///< λ, k, budget per step (max_evaluations, time_limit_seconds), estimates, threads
  int max_rows = 0;           ///< stop after this many rows (0 = until no pair can be cancelled)
  int min_branch_points = 0;  ///< stop once the count is at or below this
  /// Start from curl reduction with creation (Figure 6.5's right end, many branch points); false starts from the
  /// field's own branch points moved by curl reduction without creation (cheaper).
  bool allow_creation = true;
};

/// Rows sorted by increasing branch point count (one row per state reached; at most one row per count: if
/// several states share a count, the last one reached is kept).
/// \pre field came from compute_frame_field_detailed on `mesh`. \throw NumericalError if a factorization fails.
std::vector<BalancingSweepRow> balancing_sweep(const Mesh& mesh, const FrameFieldResult& field,
                                               const BalancingSweepOptions& options = {},
                                               ProgressSink& progress = null_progress());

}  // namespace quadcover
