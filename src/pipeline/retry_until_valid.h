#pragma once
// The loop of the validity retries (pipeline/validity_retries.h), shared by the param and the remesh job.
#include <utility>
#include <vector>

#include "common/progress.h"
#include "pipeline/parameterize_mesh.h"
#include "pipeline/validity_retries.h"

namespace quadcover {

/// Attempt 0 = run(given minus its retries), then, while the best so far is worth_retrying, up to
/// given.validity_retries further attempts run(attempt_options(given, h0, k)), keeping the best by `judge`. The
/// kept job's ParamJob (param_job(job)) records the attempts; a warning says when the kept one is not the first or
/// is not valid. A time limit or Ctrl-C ends the retries (recorded as cut short).
/// \throw InputError for invalid options (validate).
template <class Run, class Judge>
auto retry_until_valid(const PipelineOptions& given, Run run, Judge judge, ProgressSink& progress) {
  validate(given);
  PipelineOptions once = given;
  once.validity_retries = 0;
  auto first = run(once);
  using Job = decltype(first);
  Validity best_validity = judge(first);
  std::vector<ValidityAttempt> attempts{{1.0, param_job(first).map.edge_length, best_validity}};
  const double h0 = param_job(first).options.param.density.edge_length;
  int used = 0;
  Job best = std::move(first);
  for (int k = 1; k <= given.validity_retries && best_validity.worth_retrying(); ++k) {
    if (progress.skip_improvements()) {
      record_cut_short(param_job(best), "validity retries");
      break;
    }
    progress.report("retry", -1, "result not valid: attempt " + std::to_string(k + 1) + " at a nearby density");
    Job next = run(attempt_options(given, h0, k));
    const Validity v = judge(next);
    attempts.push_back({attempt_quads_factor(k, given.param.density), param_job(next).map.edge_length, v});
    if (v < best_validity) best = std::move(next), best_validity = v, used = k;
  }
  ParamJob& kept = param_job(best);
  kept.validity_attempts = attempts;
  kept.validity_attempt_used = used;
  kept.options.validity_retries = given.validity_retries;  // the attempts ran without; the job had these
  if (used > 0 || !best_validity.valid()) kept.warnings.push_back(validity_warning(attempts, used));
  return best;
}

}  // namespace quadcover
