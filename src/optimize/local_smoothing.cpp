#include "optimize/local_smoothing.h"

#include <Eigen/SparseCore>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "field/matching.h"

namespace quadcover {

SmoothingSystem::SmoothingSystem(const Mesh& mesh, const FrameSmoother& smoother)
    : mesh_(&mesh), smoother_(&smoother), lambda_(smoother.lambda()), omega_(smoother.edge_weights()),
      fixed_(smoother.fixed_faces()) {
  const int nf = mesh.num_faces();
  if (fixed_.size() != static_cast<std::size_t>(nf) || omega_.size() != mesh.num_edges())
    throw std::invalid_argument("SmoothingSystem: the smoother does not match the mesh");
  // A_tt (5.4): λ Σ_e ω_e over the interior edges of t + (1-λ) a_t, at the free faces.
  diag_ = Eigen::VectorXd::Zero(nf);
  for (int f = 0; f < nf; ++f)
    if (is_free(f)) diag_[f] = (1 - lambda_) * smoother.alignment_weights()[f];
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    for (const int f : {mesh.EF()(e, 0), mesh.EF()(e, 1)})
      if (is_free(f)) diag_[f] += lambda_ * omega_[e];
  }
}

int SmoothingSystem::rhs_change(int e, int k, double& theta, FaceEntry out[2]) const {
  if (k == 0 || mesh_->is_boundary_edge(e)) return 0;
  const double updated = wrap_angle(theta - 0.5 * std::numbers::pi * k);  // as FrameSmoother::change_matching
  const double d = theta - updated;
  theta = updated;
  int n = 0;
  const int s = mesh_->EF()(e, 0), t = mesh_->EF()(e, 1);
  if (is_free(s)) out[n++] = {s, -lambda_ * omega_[e] * d};  // (5.2.2)
  if (is_free(t)) out[n++] = {t, lambda_ * omega_[e] * d};
  return n;
}

Eigen::VectorXd SmoothingSystem::solve(const Eigen::VectorXd& rhs) const { return smoother_->solve_system(rhs); }

Eigen::VectorXd SmoothingSystem::multiply(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(x.size());
  for (int f = 0; f < mesh_->num_faces(); ++f) {
    if (!is_free(f)) continue;
    double s = diag_[f] * x[f];
    for (int k = 0; k < 3; ++k) {
      const int g = mesh_->neighbor(f, k);
      if (g >= 0 && is_free(g)) s -= lambda_ * omega_[mesh_->FE()(f, k)] * x[g];
    }
    y[f] = s;
  }
  return y;
}

void SmoothingSystem::solve_local(std::span<const FaceEntry> rhs, int rings, double tol, LocalSmoothingWork& w) const {
  const int nf = mesh_->num_faces();
  if (static_cast<int>(w.stamp.size()) != nf)
    w.stamp.assign(static_cast<std::size_t>(nf), 0), w.local.resize(w.stamp.size()), w.current = 0;
  if (++w.current == 0) std::fill(w.stamp.begin(), w.stamp.end(), 0), w.current = 1;
  w.faces.clear();
  auto add = [&](int f) {
    if (f < 0 || !is_free(f) || w.stamp[static_cast<std::size_t>(f)] == w.current) return;
    w.stamp[static_cast<std::size_t>(f)] = w.current;
    w.local[static_cast<std::size_t>(f)] = static_cast<int>(w.faces.size());
    w.faces.push_back(f);
  };
  for (const auto& e : rhs) add(e.face);
  // Breadth-first rings of free faces (deterministic order).
  std::size_t begin = 0;
  for (int ring = 0; ring < rings; ++ring) {
    const std::size_t end = w.faces.size();
    if (begin == end) break;
    for (std::size_t i = begin; i < end; ++i)
      for (int k = 0; k < 3; ++k) add(mesh_->neighbor(w.faces[i], k));
    begin = end;
  }
  const std::size_t n = w.faces.size();
  w.x.assign(n, 0.0), w.r.assign(n, 0.0), w.p.assign(n, 0.0), w.q.assign(n, 0.0), w.diag.resize(n);
  for (const auto& e : rhs)
    if (is_free(e.face)) w.r[static_cast<std::size_t>(w.local[static_cast<std::size_t>(e.face)])] += e.value;
  for (std::size_t i = 0; i < n; ++i) w.diag[i] = diag_[w.faces[i]];
  // A_PP y (Dirichlet: neighbours outside P contribute nothing).
  auto apply = [&](const std::vector<double>& y, std::vector<double>& out) {
    for (std::size_t i = 0; i < n; ++i) {
      const int f = w.faces[i];
      double s = w.diag[i] * y[i];
      for (int k = 0; k < 3; ++k) {
        const int g = mesh_->neighbor(f, k);
        if (g >= 0 && w.stamp[static_cast<std::size_t>(g)] == w.current)
          s -= lambda_ * omega_[mesh_->FE()(f, k)] * y[static_cast<std::size_t>(w.local[static_cast<std::size_t>(g)])];
      }
      out[i] = s;
    }
  };
  double r0 = 0;
  for (double v : w.r) r0 += v * v;
  if (r0 == 0) return;
  // Jacobi-preconditioned conjugate gradients (A_PP is SPD).
  double rz = 0;
  for (std::size_t i = 0; i < n; ++i) w.p[i] = w.r[i] / w.diag[i], rz += w.r[i] * w.p[i];
  const double stop = tol * tol * r0;
  for (std::size_t it = 0; it < 4 * n + 10; ++it) {
    apply(w.p, w.q);
    double pq = 0;
    for (std::size_t i = 0; i < n; ++i) pq += w.p[i] * w.q[i];
    const double a = rz / pq;
    double rr = 0;
    for (std::size_t i = 0; i < n; ++i) w.x[i] += a * w.p[i], w.r[i] -= a * w.q[i], rr += w.r[i] * w.r[i];
    if (rr <= stop) break;
    double rz_new = 0;
    for (std::size_t i = 0; i < n; ++i) rz_new += w.r[i] * w.r[i] / w.diag[i];
    const double beta = rz_new / rz;
    rz = rz_new;
    for (std::size_t i = 0; i < n; ++i) w.p[i] = w.r[i] / w.diag[i] + beta * w.p[i];
  }
}

}  // namespace quadcover
