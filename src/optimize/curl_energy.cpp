#include "optimize/curl_energy.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/errors.h"
#include "common/quarter_turn.h"
#include "cover/complex_stiffness.h"

namespace quadcover {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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

struct CurlEnergy::Workspaces {
  tbb::enumerable_thread_specific<EstimateWorkspace> per_thread;
  EstimateWorkspace serial;
};

CurlEnergy::CurlEnergy(const Mesh& mesh, FrameSmoother& smoother, const CurlEnergyOptions& options)
    : system_(mesh, smoother), workspaces_(std::make_unique<Workspaces>()), mesh_(&mesh), smoother_(&smoother),
      options_(options) {
  recompute_from_scratch();
}

CurlEnergy::~CurlEnergy() = default;
CurlEnergy::CurlEnergy(CurlEnergy&&) noexcept = default;

// 𝔏̄* + εI with v = 0 on boundary edges (1.2.4), as parameterize() solves it: a boundary edge's row and column keep
// only their diagonal and its right-hand side is 0 (rhs()), so v_b = 0 and it adds nothing to E_D.
Eigen::SparseMatrix<Complex> CurlEnergy::shifted_stiffness() const {
  Eigen::SparseMatrix<Complex> A = complex_nonconforming_stiffness(*mesh_, smoother_->matching());
  A.prune([&](Eigen::Index i, Eigen::Index j, const Complex&) {
    return i == j || (!mesh_->is_boundary_edge(static_cast<int>(i)) && !mesh_->is_boundary_edge(static_cast<int>(j)));
  });
  double mean = 0;
  for (int i = 0; i < A.rows(); ++i) mean += std::abs(A.coeff(i, i));
  mean /= std::max<Eigen::Index>(1, A.rows());
  Eigen::SparseMatrix<Complex> I(A.rows(), A.cols());
  I.setIdentity();
  return A + (options_.diagonal_shift * mean) * I;
}

double CurlEnergy::recompute_from_scratch() {
  mu_ = edge_layers(*mesh_, smoother_->matching());
  X0_ = smoother_->rotated(Eigen::VectorXd::Zero(mesh_->num_faces())).X;
  edge_vec_.resize(mesh_->num_faces(), 3);
  for (int f = 0; f < mesh_->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) edge_vec_(f, k) = mesh_->edge_vector_local(f, k);
  // The smoothing solve (5.3) and the factorization of 𝔏̄* are independent: one per core.
  tbb::parallel_invoke([&] { alpha_ = smoother_->solve(); }, [&] { factor_ = UpdatableCholesky(shifted_stiffness()); });
  field_ = smoother_->rotated(alpha_);
  factor_.set_rhs(rhs(alpha_));  // 𝔏̄* v = -curl* X (6.1)
  trial_ = FactorTrial(factor_.size());
  pending_valid_ = false;
  estimates_ready_ = false;
  solution_valid_ = false;
  commits_since_prepare_ = 0;
  return energy();
}

// Layer μ of edge e in its non-reference face for matching value m (cover/complex_stiffness.h: the reference
// face r is the one with the smaller index; crossing from r into the other face shifts layers by ∓m).
int CurlEnergy::layer_after(int e, int m) const {
  const int s = mesh_->EF()(e, 0), t = mesh_->EF()(e, 1);
  const int r = std::min(s, t);
  return mod4(r == s ? -m : m);
}

template <class Layer>
StarChange CurlEnergy::star_change(int e, int new_matching, Layer mu) const {
  StarChange c;
  c.k = e;
  const int g = std::max(mesh_->EF()(e, 0), mesh_->EF()(e, 1));  // non-reference face: its layer of e changes
  int a = 0;
  while (mesh_->FE()(g, a) != e) ++a;
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

StarChange CurlEnergy::stiffness_change(int e, int delta) const {
  if (delta == 0 || mesh_->is_boundary_edge(e)) return StarChange{e, {}};
  return star_change(e, field_.matching[e] + delta, [&](int f, int k) { return mu_(f, k); });
}

double CurlEnergy::curvature(int e) const {
  if (mesh_->is_boundary_edge(e)) return 0;
  return smoother_->curvature()[e] - alpha_[mesh_->EF()(e, 0)] + alpha_[mesh_->EF()(e, 1)];
}

double CurlEnergy::evaluate(std::span<const MatchingChange> changes) {
  ++timings_.evaluations;
  auto t0 = Clock::now();
  pending_.assign(changes.begin(), changes.end());
  pending_valid_ = false;
  // min E(α) with the new matching (5.2.2), then the rotated field; the smoother is restored afterwards.
  for (const auto& c : changes) smoother_->change_matching(c.edge, c.delta);
  pending_alpha_ = smoother_->solve();
  for (auto it = changes.rbegin(); it != changes.rend(); ++it) smoother_->change_matching(it->edge, -it->delta);
  timings_.smoothing += seconds_since(t0);
  // Star changes one edge at a time (a path may cross the same face twice: layers are updated as we go).
  t0 = Clock::now();
  trial_.reset();
  bool ok = true;
  std::vector<std::tuple<int, int, int>> saved;  // (face, slot, old μ)
  for (const auto& c : changes) {
    if (mesh_->is_boundary_edge(c.edge) || c.delta == 0) continue;
    const StarChange star = stiffness_change(c.edge, c.delta);
    ok = ok && trial_.add_star_change(factor_, star);
    const int g = std::max(mesh_->EF()(c.edge, 0), mesh_->EF()(c.edge, 1));
    int a = 0;
    while (mesh_->FE()(g, a) != c.edge) ++a;
    saved.emplace_back(g, a, mu_(g, a));
    field_.matching[c.edge] += c.delta;
    mu_(g, a) = layer_after(c.edge, field_.matching[c.edge]);
  }
  timings_.update += seconds_since(t0);
  t0 = Clock::now();
  const Eigen::VectorXcd b = rhs(pending_alpha_);  // -curl* of the re-smoothed field with the new layers
  timings_.curl += seconds_since(t0);
  for (auto it = saved.rbegin(); it != saved.rend(); ++it) mu_(std::get<0>(*it), std::get<1>(*it)) = std::get<2>(*it);
  for (const auto& c : changes)
    if (!mesh_->is_boundary_edge(c.edge)) field_.matching[c.edge] -= c.delta;
  if (!ok) return std::numeric_limits<double>::infinity();
  t0 = Clock::now();
  const double e = trial_.evaluate_full(factor_, b);
  timings_.solve += seconds_since(t0);
  pending_valid_ = true;
  return e;
}

void CurlEnergy::commit() {
  if (!pending_valid_) throw NumericalError("curl reduction", "commit without a valid evaluation");
  const auto t_commit = Clock::now();
  for (const auto& c : pending_) {
    if (mesh_->is_boundary_edge(c.edge) || c.delta == 0) continue;
    smoother_->change_matching(c.edge, c.delta);
    const int g = std::max(mesh_->EF()(c.edge, 0), mesh_->EF()(c.edge, 1));
    int a = 0;
    while (mesh_->FE()(g, a) != c.edge) ++a;
    mu_(g, a) = layer_after(c.edge, smoother_->matching()[c.edge]);
  }
  alpha_ = pending_alpha_;
  field_ = smoother_->rotated(alpha_);
  trial_.commit(factor_);
  trial_.reset();
  pending_valid_ = false;
  estimates_ready_ = false;
  solution_valid_ = false;
  ++commits_since_prepare_;
  timings_.commit += seconds_since(t_commit);
}

// One face's term of -curl* (3.3) at its edge k for the rotated frame X = e^{iα}X⁰_f (Y = iX) on layer μ:
// conj(i^μ) ⟨Z_f, e⟩ with ⟨Z, e⟩ = ⟨X, e⟩ + i⟨Y, e⟩ (the sum of cover/complex_stiffness.cpp, with cached edge
// vectors and layers instead of a global layer recomputation).
Complex CurlEnergy::term(int f, int k, Complex X, int mu) const {
  const Complex ce = std::conj(edge_vec_(f, k));
  return ipow(-mu) * Complex(std::real(ce * X), std::real(ce * Complex(-X.imag(), X.real())));
}

Complex CurlEnergy::contribution(int f, int k, double alpha, int mu) const {
  return term(f, k, std::polar(1.0, alpha) * X0_[f], mu);
}

// -curl* of the field e^{iα}X⁰ with the current layers: one rotation per face (not one per face edge).
Eigen::VectorXcd CurlEnergy::rhs(const Eigen::VectorXd& alpha) const {
  Eigen::VectorXcd b = Eigen::VectorXcd::Zero(mesh_->num_edges());
  for (int f = 0; f < mesh_->num_faces(); ++f) {
    const Complex X = std::polar(1.0, alpha[f]) * X0_[f];
    for (int k = 0; k < 3; ++k) b[mesh_->FE()(f, k)] += term(f, k, X, mu_(f, k));
  }
  for (int e = 0; e < mesh_->num_edges(); ++e)
    if (mesh_->is_boundary_edge(e)) b[e] = 0;  // v = 0 there (shifted_stiffness)
  return b;
}

const Eigen::VectorXcd& CurlEnergy::solution() const {
  if (!solution_valid_) {
    const auto t0 = Clock::now();
    solution_ = factor_.solve_full();  // v = 𝔏̄*⁻¹(-curl*X): the forward solution x, then the back substitution
    solution_valid_ = true;
    timings_.shares += seconds_since(t0);
  }
  return solution_;
}

Eigen::VectorXd CurlEnergy::distortion_shares() const {
  const Eigen::VectorXcd& v = solution();      // Algorithm 6.1 step 2
  const Eigen::VectorXcd& bp = factor_.rhs();  // permuted
  Eigen::VectorXd share(v.size());
  for (int i = 0; i < factor_.size(); ++i) {
    const int e = factor_.perm()[i];
    share[e] = std::abs(std::real(std::conj(v[e]) * bp[i]));
  }
  return share;
}

// ∇_α E_D: E_D = bᴴ𝔏̄*⁻¹b, so ∂E_D/∂α_f = 2 Re(vᴴ ∂b/∂α_f) with v = 𝔏̄*⁻¹b; ∂/∂α_f of face f's term c_fk is
// -i·c_fk (the term is linear in conj(X_f) = e^{-iα_f} conj(X⁰_f)). z = A⁻¹∇_α E_D (5.4).
void CurlEnergy::prepare_estimates() {
  if (estimates_ready_) return;
  // Stale by fewer than estimate_refresh commits: the far-field correction of the screening estimates uses the
  // older ∇_α E_D and z (the local part of every estimate always uses the current factor and field).
  if (commits_since_prepare_ > 0 && commits_since_prepare_ < options_.estimate_refresh) {
    estimates_ready_ = true;
    return;
  }
  const auto t0 = Clock::now();
  const Eigen::VectorXcd& v = solution();
  grad_ = Eigen::VectorXd::Zero(mesh_->num_faces());
  for (int f = 0; f < mesh_->num_faces(); ++f) {
    if (!system_.is_free(f)) continue;
    const Complex X = std::polar(1.0, alpha_[f]) * X0_[f];
    double g = 0;
    for (int k = 0; k < 3; ++k)
      g += std::real(std::conj(v[mesh_->FE()(f, k)]) * Complex(0, -1) * term(f, k, X, mu_(f, k)));
    grad_[f] = 2 * g;
  }
  adjoint_ = system_.solve(grad_);
  estimates_ready_ = true;
  commits_since_prepare_ = 0;
  timings_.prepare += seconds_since(t0);
  ++timings_.prepares;
}

double CurlEnergy::estimate(std::span<const MatchingChange> changes, EstimateWorkspace& ws) const {
  return estimate(changes, ws, options_.local_rings);
}

double CurlEnergy::estimate(std::span<const MatchingChange> changes, EstimateWorkspace& ws, int rings) const {
  if (!estimates_ready_) throw std::logic_error("CurlEnergy::estimate before prepare_estimates");
  next_stamp(ws, mesh_->num_faces(), mesh_->num_edges());
  auto t0 = Clock::now();
  ws.m_override.clear(), ws.theta_override.clear(), ws.mu_override.clear(), ws.db_smooth.clear();
  auto layer = [&](int f, int k) {
    for (auto it = ws.mu_override.rbegin(); it != ws.mu_override.rend(); ++it)
      if (std::get<0>(*it) == f && std::get<1>(*it) == k) return std::get<2>(*it);
    return mu_(f, k);
  };
  ws.trial.reset();
  bool ok = true;
  for (const auto& c : changes) {
    if (mesh_->is_boundary_edge(c.edge) || c.delta == 0) continue;
    int m = field_.matching[c.edge];
    double theta = smoother_->curvature()[c.edge];
    for (auto& [e, v] : ws.m_override)
      if (e == c.edge) m = v;
    for (auto& [e, v] : ws.theta_override)
      if (e == c.edge) theta = v;
    FaceEntry fe[2];
    const int n = system_.rhs_change(c.edge, c.delta, theta, fe);  // Δb of (5.4), θ_e updated
    ws.db_smooth.insert(ws.db_smooth.end(), fe, fe + n);
    // Star change of 𝔏̄* one edge at a time with the layers as changed so far (6.2.1).
    ok = ok && ws.trial.add_star_change(factor_, star_change(c.edge, m + c.delta, layer));
    const int g = std::max(mesh_->EF()(c.edge, 0), mesh_->EF()(c.edge, 1));
    int a = 0;
    while (mesh_->FE()(g, a) != c.edge) ++a;
    ws.mu_override.emplace_back(g, a, layer_after(c.edge, m + c.delta));
    ws.m_override.emplace_back(c.edge, m + c.delta);
    ws.theta_override.emplace_back(c.edge, theta);
  }
  ws.timings.update += seconds_since(t0);
  if (!ok) return std::numeric_limits<double>::infinity();
  t0 = Clock::now();
  // Local re-smoothing Δα_P (SmoothingSystem::solve_local).
  system_.solve_local(ws.db_smooth, rings, options_.local_tolerance, ws.smoothing);
  ws.timings.smoothing += seconds_since(t0);
  t0 = Clock::now();
  // Δ(-curl*X) on the edges of the faces whose angle or layers changed: a sparse right-hand side change.
  ws.db_curl.clear();
  auto add_face = [&](int f, double dalpha) {
    if (ws.face_stamp[static_cast<std::size_t>(f)] == ws.stamp) return;
    ws.face_stamp[static_cast<std::size_t>(f)] = ws.stamp;
    const Complex X = std::polar(1.0, alpha_[f]) * X0_[f];
    const Complex Xn = dalpha == 0.0 ? X : std::polar(1.0, alpha_[f] + dalpha) * X0_[f];
    for (int k = 0; k < 3; ++k) {
      const int e = mesh_->FE()(f, k);
      if (mesh_->is_boundary_edge(e)) continue;  // pinned: its right-hand side stays 0
      const Complex d = term(f, k, Xn, layer(f, k)) - term(f, k, X, mu_(f, k));
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
  ws.trial.add_rhs_change(factor_, ws.db_curl);
  // First-order far field: zᵀΔb - (∇_α E_D)ᵀΔα_P.
  double correction = 0;
  for (const auto& fe : ws.db_smooth) correction += adjoint_[fe.face] * fe.value;
  for (std::size_t i = 0; i < patch.size(); ++i) correction -= grad_[patch[i]] * ws.smoothing.x[i];
  ws.timings.curl += seconds_since(t0);
  t0 = Clock::now();
  const double e_local = ws.trial.evaluate(factor_);  // reach-limited forward solve
  ws.timings.solve += seconds_since(t0);
  ++ws.timings.evaluations;
  ws.patch_faces += static_cast<long>(patch.size());
  ws.reach_columns += ws.trial.reach();
  return e_local + correction;
}

void CurlEnergy::estimate_batch(std::span<const std::vector<MatchingChange>> candidates, std::span<double> out,
                                int threads) {
  prepare_estimates();
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

CurlEnergyTimings CurlEnergy::estimate_timings() const {
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
