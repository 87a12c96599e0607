#include "optimize/balancing_sweep.h"

#include <algorithm>
#include <limits>
#include <map>

namespace quadcover {

std::vector<BalancingSweepRow> balancing_sweep(const Mesh& mesh, const FrameFieldResult& field,
                                               const BalancingSweepOptions& options, ProgressSink& progress) {
  const OptimizeOptions& oo = options.optimize;
  FrameSmoother smoother(mesh, field.field, field.stability, field.trusted, field.constrained, oo.lambda);
  CurlEnergy energy(mesh, smoother, oo.energy);
  CurlEstimator screening(energy);
  CurlReductionOptions ro = curl_reduction_options(oo);
  ro.allow_creation = options.allow_creation;  // with creation: the right end of Figure 6.5
  CurlReductionResult r = reduce_curl(mesh, energy, ro, progress, &screening);
  long evaluations = r.evaluations;
  // Settle: Steps 1-3 without creation until nothing is accepted, so that every row is a local minimum for
  // single-edge moves and for the cancellations of Step 1 (those lower E_D and would otherwise fall into the
  // next row).
  auto settle = [&] {
    CurlReductionOptions so = ro;
    so.allow_creation = false;
    so.delta_eh = 0;  // no balancing while settling
    for (long accepted = 1; accepted > 0 && !progress.cancelled();) {
      const CurlReductionResult s = reduce_curl(mesh, energy, so, progress, &screening);
      evaluations += s.evaluations;
      accepted = s.accepted;
      r.final_branch_points = s.final_branch_points;
    }
  };
  settle();
  std::map<int, BalancingSweepRow> rows;
  auto record = [&](int bp) {
    const Parameterization p = parameterize(mesh, energy.field(), oo.param, progress);
    rows[bp] = {bp, energy.energy(), p.energy_harmonic, energy.energy() + p.energy_harmonic, p.h_sym, evaluations};
  };
  record(r.final_branch_points);
  // Step 4 one pair at a time: Δ_EH = ∞ cancels the cheapest pair, then curl reduction without creation.
  ro.allow_creation = false;
  ro.delta_eh = std::numeric_limits<double>::infinity();
  ro.max_balancing_rounds = 1;
  ro.max_cancellations_per_round = 1;
  int bp = r.final_branch_points;
  while (!progress.cancelled() && bp > options.min_branch_points &&
         (options.max_rows <= 0 || static_cast<int>(rows.size()) < options.max_rows)) {
    r = reduce_curl(mesh, energy, ro, progress, &screening);
    evaluations += r.evaluations;
    if (r.cancelled_pairs == 0) break;
    settle();
    bp = r.final_branch_points;
    record(bp);
  }
  std::vector<BalancingSweepRow> out;
  for (const auto& [count, row] : rows) out.push_back(row);
  return out;
}

}  // namespace quadcover
