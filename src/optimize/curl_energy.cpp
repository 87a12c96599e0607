#include "optimize/curl_energy.h"

#include <chrono>
#include <cmath>
#include <limits>

#include "common/errors.h"
#include "cover/complex_stiffness.h"

namespace quadcover {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

int mod4(int k) { return ((k % 4) + 4) % 4; }

}  // namespace

CurlEnergy::CurlEnergy(const Mesh& mesh, FrameSmoother& smoother, const CurlEnergyOptions& options)
    : mesh_(&mesh), smoother_(&smoother), options_(options) {
  recompute_from_scratch();
}

Eigen::SparseMatrix<Complex> CurlEnergy::shifted_stiffness() const {
  Eigen::SparseMatrix<Complex> A = complex_nonconforming_stiffness(*mesh_, smoother_->matching());
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
  alpha_ = smoother_->solve();
  field_ = smoother_->rotated(alpha_);
  factor_ = UpdatableCholesky(shifted_stiffness());
  factor_.set_rhs(-complex_curl_star(*mesh_, field_));  // 𝔏̄* v = -curl* X (6.1)
  trial_ = FactorTrial(factor_.size());
  pending_valid_ = false;
  return energy();
}

// Layer μ of edge e in its non-reference face for matching value m (cover/complex_stiffness.h: the reference
// face r is the one with the smaller index; crossing from r into the other face shifts layers by ∓m).
int CurlEnergy::layer_after(int e, int m) const {
  const int s = mesh_->EF()(e, 0), t = mesh_->EF()(e, 1);
  const int r = std::min(s, t);
  return mod4(r == s ? -m : m);
}

StarChange CurlEnergy::stiffness_change(int e, int delta) const {
  StarChange c;
  c.k = e;
  if (delta == 0 || mesh_->is_boundary_edge(e)) return c;
  const int g = std::max(mesh_->EF()(e, 0), mesh_->EF()(e, 1));  // non-reference face: its layer of e changes
  int a = 0;
  while (mesh_->FE()(g, a) != e) ++a;
  const int mu_new = layer_after(e, field_.matching[e] + delta);
  const double area = mesh_->face_areas()[g];
  for (int b = 0; b < 3; ++b) {
    if (b == a) continue;
    // 𝔏̄*(e, e_b) from face g = K_ab i^{μ_b - μ_a} (3.8), K_ab = ⟨e_a, e_b⟩ / A_g (1.5).
    const double K = std::real(std::conj(mesh_->edge_vector_local(g, a)) * mesh_->edge_vector_local(g, b)) / area;
    c.d.push_back({mesh_->FE()(g, b), K * (ipow(mu_(g, b) - mu_new) - ipow(mu_(g, b) - mu_(g, a)))});
  }
  return c;
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
  const double e = 0.5 * trial_.evaluate_full(factor_, b);
  timings_.solve += seconds_since(t0);
  pending_valid_ = true;
  return e;
}

void CurlEnergy::commit() {
  if (!pending_valid_) throw NumericalError("curl reduction", "commit without a valid evaluation");
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
}

// -curl* (3.3) of X_f = e^{iα_f} X⁰_f (Y = iX) with the layers μ: b_e = Σ_f conj(i^{μ(f,k)}) ⟨Z_f, e_f⟩, the same
// sum as cover/complex_stiffness.cpp but with cached edge vectors and layers (no global layer recomputation).
Eigen::VectorXcd CurlEnergy::rhs(const Eigen::VectorXd& alpha) const {
  Eigen::VectorXcd b = Eigen::VectorXcd::Zero(mesh_->num_edges());
  for (int f = 0; f < mesh_->num_faces(); ++f) {
    const Complex X = std::polar(1.0, alpha[f]) * X0_[f];
    for (int k = 0; k < 3; ++k) {
      const Complex ce = std::conj(edge_vec_(f, k));
      const Complex ez(std::real(ce * X), std::real(ce * Complex(-X.imag(), X.real())));
      b[mesh_->FE()(f, k)] += ipow(-mu_(f, k)) * ez;
    }
  }
  return b;
}

Eigen::VectorXd CurlEnergy::distortion_shares() const {
  const Eigen::VectorXcd v = factor_.solve_full();  // forward and back substitution (Algorithm 6.1 step 2)
  const Eigen::VectorXcd& bp = factor_.rhs();       // permuted
  Eigen::VectorXd share(v.size());
  for (int i = 0; i < factor_.size(); ++i) {
    const int e = factor_.perm()[i];
    share[e] = std::abs(std::real(std::conj(v[e]) * bp[i]));
  }
  return share;
}

}  // namespace quadcover
