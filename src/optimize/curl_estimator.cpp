#include "optimize/curl_estimator.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/seconds_since.h"

namespace quadcover {

namespace {

// Sizes the workspace's face/edge stamps for the mesh and starts a new stamp (clearing them only on wrap-around).
void next_stamp(EstimateWorkspace& ws, int nf, int ne) {
  if (static_cast<int>(ws.face_stamp.size()) != nf || static_cast<int>(ws.edge_stamp.size()) != ne) {
    ws.face_stamp.assign(static_cast<std::size_t>(nf), 0);
    ws.edge_stamp.assign(static_cast<std::size_t>(ne), 0);
    ws.edge_slot.assign(static_cast<std::size_t>(ne), 0);
    ws.stamp = 0;
  }
  if (++ws.stamp == 0) {
    std::fill(ws.face_stamp.begin(), ws.face_stamp.end(), 0);
    std::fill(ws.edge_stamp.begin(), ws.edge_stamp.end(), 0);
    ws.stamp = 1;
  }
}

}  // namespace

struct CurlEstimator::Workspaces {
  tbb::enumerable_thread_specific<EstimateWorkspace> per_thread;
  EstimateWorkspace serial;
};

CurlEstimator::CurlEstimator(CurlEnergy& energy)
    : energy_(&energy), system_(*energy.mesh_, *energy.smoother_), workspaces_(std::make_unique<Workspaces>()) {}

CurlEstimator::~CurlEstimator() = default;

bool CurlEstimator::ready() const {
  return energy_->rebuilds_ == prepared_rebuilds_ && energy_->commits_ == ready_commits_;
}

// ∇_α E_D: E_D = bᴴ𝔏̄*⁻¹b, so ∂E_D/∂α_f = 2 Re(vᴴ ∂b/∂α_f) with v = 𝔏̄*⁻¹b; ∂/∂α_f of face f's term c_fk is
// -i·c_fk (the term is linear in conj(X_f) = e^{-iα_f} conj(X⁰_f)). z = A⁻¹∇_α E_D (5.4).
void CurlEstimator::prepare() {
  const CurlEnergy& E = *energy_;
  if (ready()) return;
  // Stale by fewer than estimate_refresh commits: the far-field correction of the screening estimates uses the
  // older ∇_α E_D and z (the local part of every estimate always uses the current factor and field).
  const long since = E.commits_ - prepared_commits_;
  if (E.rebuilds_ == prepared_rebuilds_ && since > 0 && since < E.options_.estimate_refresh) {
    ready_commits_ = E.commits_;
    return;
  }
  const auto t0 = SteadyClock::now();
  const Eigen::VectorXcd& v = E.solution();
  grad_ = Eigen::VectorXd::Zero(E.mesh_->num_faces());
  for (int f = 0; f < E.mesh_->num_faces(); ++f) {
    if (!system_.is_free(f)) continue;
    const Complex X = E.rotated_frame(f, E.alpha_[f]);
    double g = 0;
    for (int k = 0; k < 3; ++k)
      g += std::real(std::conj(v[E.mesh_->FE()(f, k)]) * Complex(0, -1) * E.term(f, k, X, E.mu_(f, k)));
    grad_[f] = 2 * g;
  }
  adjoint_ = system_.solve(grad_);
  prepared_commits_ = ready_commits_ = E.commits_;
  prepared_rebuilds_ = E.rebuilds_;
  E.timings_.prepare += seconds_since(t0);
  ++E.timings_.prepares;
}

double CurlEstimator::estimate(std::span<const MatchingChange> changes, EstimateWorkspace& ws) const {
  const CurlEnergy& E = *energy_;
  return estimate(changes, ws, E.options_.local_rings);
}

double CurlEstimator::estimate(std::span<const MatchingChange> changes, EstimateWorkspace& ws, int rings) const {
  const CurlEnergy& E = *energy_;
  if (!ready()) throw std::logic_error("CurlEstimator::estimate before prepare");
  next_stamp(ws, E.mesh_->num_faces(), E.mesh_->num_edges());
  auto t0 = SteadyClock::now();
  ws.m_override.clear(), ws.theta_override.clear(), ws.mu_override.clear(), ws.db_smooth.clear();
  auto layer = [&](int f, int k) {
    for (auto it = ws.mu_override.rbegin(); it != ws.mu_override.rend(); ++it)
      if (std::get<0>(*it) == f && std::get<1>(*it) == k) return std::get<2>(*it);
    return E.mu_(f, k);
  };
  ws.trial.reset();
  bool ok = true;
  for (const auto& c : changes) {
    if (E.mesh_->is_boundary_edge(c.edge) || c.delta == 0) continue;
    int m = E.field_.matching[c.edge];
    double theta = E.smoother_->curvature()[c.edge];
    for (auto& [e, v] : ws.m_override)
      if (e == c.edge) m = v;
    for (auto& [e, v] : ws.theta_override)
      if (e == c.edge) theta = v;
    FaceEntry fe[2];
    const int n = system_.rhs_change(c.edge, c.delta, theta, fe);  // Δb of (5.4), θ_e updated
    ws.db_smooth.insert(ws.db_smooth.end(), fe, fe + n);
    // Star change of 𝔏̄* one edge at a time with the layers as changed so far (6.2.1).
    ok = ok && ws.trial.add_star_change(E.factor_, E.star_change(c.edge, m + c.delta, layer));
    const auto [g, a] = E.changed_slot(c.edge);
    ws.mu_override.emplace_back(g, a, E.layer_after(c.edge, m + c.delta));
    ws.m_override.emplace_back(c.edge, m + c.delta);
    ws.theta_override.emplace_back(c.edge, theta);
  }
  ws.timings.update += seconds_since(t0);
  if (!ok) return std::numeric_limits<double>::infinity();
  t0 = SteadyClock::now();
  // Local re-smoothing Δα_P (SmoothingSystem::solve_local).
  system_.solve_local(ws.db_smooth, rings, E.options_.local_tolerance, ws.smoothing);
  ws.timings.smoothing += seconds_since(t0);
  t0 = SteadyClock::now();
  // Δ(-curl*X) on the edges of the faces whose angle or layers changed: a sparse right-hand side change.
  ws.db_curl.clear();
  auto add_face = [&](int f, double dalpha) {
    if (ws.face_stamp[static_cast<std::size_t>(f)] == ws.stamp) return;
    ws.face_stamp[static_cast<std::size_t>(f)] = ws.stamp;
    const Complex X = E.rotated_frame(f, E.alpha_[f]);
    const Complex Xn = dalpha == 0.0 ? X : E.rotated_frame(f, E.alpha_[f] + dalpha);
    for (int k = 0; k < 3; ++k) {
      const int e = E.mesh_->FE()(f, k);
      if (E.mesh_->is_boundary_edge(e)) continue;  // pinned: its right-hand side stays 0
      const Complex d = E.term(f, k, Xn, layer(f, k)) - E.term(f, k, X, E.mu_(f, k));
      if (ws.edge_stamp[static_cast<std::size_t>(e)] != ws.stamp) {
        ws.edge_stamp[static_cast<std::size_t>(e)] = ws.stamp;
        ws.edge_slot[static_cast<std::size_t>(e)] = static_cast<int>(ws.db_curl.size());
        ws.db_curl.push_back({e, d});
      } else {
        ws.db_curl[static_cast<std::size_t>(ws.edge_slot[static_cast<std::size_t>(e)])].value += d;
      }
    }
  };
  const auto& patch = ws.smoothing.faces;
  for (std::size_t i = 0; i < patch.size(); ++i) add_face(patch[i], ws.smoothing.x[i]);
  for (const auto& o : ws.mu_override) add_face(std::get<0>(o), 0.0);  // layer changed, angle fixed or unchanged
  ws.trial.add_rhs_change(E.factor_, ws.db_curl);
  // First-order far field: zᵀΔb - (∇_α E_D)ᵀΔα_P.
  double correction = 0;
  for (const auto& fe : ws.db_smooth) correction += adjoint_[fe.face] * fe.value;
  for (std::size_t i = 0; i < patch.size(); ++i) correction -= grad_[patch[i]] * ws.smoothing.x[i];
  ws.timings.curl += seconds_since(t0);
  t0 = SteadyClock::now();
  const double e_local = ws.trial.evaluate(E.factor_);  // reach-limited forward solve
  ws.timings.solve += seconds_since(t0);
  ++ws.timings.evaluations;
  ws.patch_faces += static_cast<long>(patch.size());
  ws.reach_columns += ws.trial.reach();
  return e_local + correction;
}

void CurlEstimator::estimate_batch(std::span<const std::vector<MatchingChange>> candidates, std::span<double> out,
                                int threads) {
  prepare();
  if (candidates.size() <= 1 || threads == 1) {
    for (std::size_t i = 0; i < candidates.size(); ++i) out[i] = estimate(candidates[i], workspaces_->serial);
    return;
  }
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, candidates.size(),
                      [&](std::size_t i) { out[i] = estimate(candidates[i], workspaces_->per_thread.local()); });
  });
}

CurlEnergyTimings CurlEstimator::timings() const {
  CurlEnergyTimings t;
  auto add = [&](const EstimateWorkspace& w) {
    t.smoothing += w.timings.smoothing, t.curl += w.timings.curl, t.update += w.timings.update;
    t.solve += w.timings.solve, t.evaluations += w.timings.evaluations;
  };
  add(workspaces_->serial);
  for (const auto& w : workspaces_->per_thread) add(w);
  return t;
}

}  // namespace quadcover
