#include "field/smoothing.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "calculus/sparse_cholesky.h"
#include "common/errors.h"
#include "field/matching.h"

namespace quadcover {

struct FrameSmoother::Solver {
  SparseCholesky<double> cholesky;  // A = L Lᵀ, factored once; each solve is two triangular solves
};

FrameSmoother::~FrameSmoother() = default;
FrameSmoother::FrameSmoother(FrameSmoother&&) noexcept = default;
FrameSmoother& FrameSmoother::operator=(FrameSmoother&&) noexcept = default;

FrameSmoother::FrameSmoother(const Mesh& mesh, const FrameField& input, const Eigen::VectorXd& stability,
                             const std::vector<char>& trusted, const std::vector<char>& fixed, double lambda)
    : FrameSmoother(mesh, stability, trusted, fixed, lambda) {
  set_input(input);
}

namespace {

// Alignment weights a_t = ω_t A_t on the trusted faces, normalized by their mean over them.
Eigen::VectorXd trusted_alignment_weights(const Mesh& mesh, const Eigen::VectorXd& stability,
                                          const std::vector<char>& trusted) {
  const int nf = mesh.num_faces();
  Eigen::VectorXd align = Eigen::VectorXd::Zero(nf);
  double sum = 0;
  int count = 0;
  for (int t = 0; t < nf; ++t)
    if (trusted[static_cast<std::size_t>(t)]) {
      align[t] = stability[t] * mesh.face_areas()[t];
      sum += align[t];
      ++count;
    }
  if (sum > 0) align *= count / sum;
  return align;
}

// Fixes the most stable face of every group of free faces that neither touches a fixed face nor has an
// alignment term ((1-λ) a_t > 0): A (5.4) would be singular there.
void anchor_free_groups(const Mesh& mesh, const Eigen::VectorXd& stability, const Eigen::VectorXd& align, double lambda,
                        std::vector<char>& fixed) {
  const int nf = mesh.num_faces();
  std::vector<int> group(static_cast<std::size_t>(nf), -1), stack;
  for (int seed = 0; seed < nf; ++seed) {
    if (fixed[static_cast<std::size_t>(seed)] || group[static_cast<std::size_t>(seed)] >= 0) continue;
    bool anchored = false;
    int best = seed;
    stack.assign(1, seed);
    group[static_cast<std::size_t>(seed)] = seed;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      if ((1 - lambda) * align[f] > 0) anchored = true;
      if (stability[f] > stability[best] || (stability[f] == stability[best] && f < best)) best = f;
      for (int k = 0; k < 3; ++k) {
        const int g = mesh.neighbor(f, k);
        if (g < 0) continue;
        if (fixed[static_cast<std::size_t>(g)]) {
          anchored = true;
        } else if (group[static_cast<std::size_t>(g)] < 0) {
          group[static_cast<std::size_t>(g)] = seed;
          stack.push_back(g);
        }
      }
    }
    if (!anchored) fixed[static_cast<std::size_t>(best)] = 1;
  }
}

// A (5.4) restricted to the free faces (fixed α = 0 moves nothing to the right-hand side).
Eigen::SparseMatrix<double> smoothing_matrix(const Mesh& mesh, const Eigen::VectorXd& omega,
                                             const Eigen::VectorXd& align, double lambda,
                                             const std::vector<int>& unknown_of_face,
                                             const std::vector<int>& unknowns) {
  const int n = static_cast<int>(unknowns.size()), ne = mesh.num_edges();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(n + 4 * ne));
  for (int i = 0; i < n; ++i) {
    const double a = (1 - lambda) * align[unknowns[static_cast<std::size_t>(i)]];
    if (a > 0) entries.emplace_back(i, i, a);
  }
  for (int e = 0; e < ne; ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    const int s = unknown_of_face[static_cast<std::size_t>(mesh.EF()(e, 0))];
    const int t = unknown_of_face[static_cast<std::size_t>(mesh.EF()(e, 1))];
    const double w = lambda * omega[e];
    if (s >= 0) entries.emplace_back(s, s, w);
    if (t >= 0) entries.emplace_back(t, t, w);
    if (s >= 0 && t >= 0) {
      entries.emplace_back(s, t, -w);
      entries.emplace_back(t, s, -w);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

}  // namespace

FrameSmoother::FrameSmoother(const Mesh& mesh, const Eigen::VectorXd& stability, const std::vector<char>& trusted,
                             const std::vector<char>& fixed, double lambda)
    : mesh_(&mesh), lambda_(lambda) {
  const int nf = mesh.num_faces();
  if (!(lambda > 0 && lambda <= 1)) throw std::invalid_argument("FrameSmoother: λ must lie in (0, 1]");
  if (stability.size() != nf || trusted.size() != static_cast<std::size_t>(nf) ||
      (!fixed.empty() && fixed.size() != static_cast<std::size_t>(nf)))
    throw std::invalid_argument("FrameSmoother: input sizes do not match the mesh");
  omega_ = smoothing_edge_weights(mesh);
  align_ = trusted_alignment_weights(mesh, stability, trusted);
  beta_ = Eigen::VectorXd::Zero(nf);
  fixed_.assign(static_cast<std::size_t>(nf), 0);
  for (std::size_t t = 0; t < fixed.size(); ++t) fixed_[t] = fixed[t];
  anchor_free_groups(mesh, stability, align_, lambda, fixed_);
  unknown_of_face_.assign(static_cast<std::size_t>(nf), -1);
  for (int t = 0; t < nf; ++t)
    if (!fixed_[static_cast<std::size_t>(t)]) {
      unknown_of_face_[static_cast<std::size_t>(t)] = static_cast<int>(unknowns_.size());
      unknowns_.push_back(t);
    }
  b_ = Eigen::VectorXd::Zero(num_unknowns());  // b in set_input
  solver_ = std::make_unique<Solver>();
  solver_->cholesky.compute(smoothing_matrix(mesh, omega_, align_, lambda, unknown_of_face_, unknowns_),
                            "field smoothing (5.4)");  // throws NumericalError if not positive definite
}

void FrameSmoother::set_input(const FrameField& input) {
  const Mesh& mesh = *mesh_;
  if (input.X.size() != mesh.num_faces() || input.matching.size() != mesh.num_edges())
    throw std::invalid_argument("FrameSmoother: input sizes do not match the mesh");
  X0_ = input.X;
  matching_ = input.matching;
  theta_ = field_curvature(mesh, make_cross_field(X0_, matching_));
  // ∂/∂α of λω(θ - α_s + α_t)²: row t gets λω(α_t - α_s) = -λωθ, row s gets λω(α_s - α_t) = λωθ; the targets β
  // of E_A add (1-λ) a_t β_t (set_alignment_targets).
  b_ = Eigen::VectorXd::Zero(num_unknowns());
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    const int s = unknown_of_face_[static_cast<std::size_t>(mesh.EF()(e, 0))];
    const int t = unknown_of_face_[static_cast<std::size_t>(mesh.EF()(e, 1))];
    const double w = lambda_ * omega_[e];
    if (s >= 0) b_[s] += w * theta_[e];
    if (t >= 0) b_[t] -= w * theta_[e];
  }
  for (std::size_t i = 0; i < unknowns_.size(); ++i) {
    const int t = unknowns_[i];
    b_[static_cast<Eigen::Index>(i)] += (1 - lambda_) * align_[t] * beta_[t];
  }
}

void FrameSmoother::change_matching(int e, int k) {
  if (k == 0 || mesh_->is_boundary_edge(e)) return;
  matching_[e] += k;
  const double updated = wrap_angle(theta_[e] - 0.5 * std::numbers::pi * k);  // θ_e - (π/2)k, as field_curvature
  const double d = theta_[e] - updated;
  theta_[e] = updated;
  const int s = unknown_of_face_[static_cast<std::size_t>(mesh_->EF()(e, 0))];
  const int t = unknown_of_face_[static_cast<std::size_t>(mesh_->EF()(e, 1))];
  if (s >= 0) b_[s] -= lambda_ * omega_[e] * d;  // (5.2.2)
  if (t >= 0) b_[t] += lambda_ * omega_[e] * d;
}

Eigen::VectorXd FrameSmoother::solve() const {
  Eigen::VectorXd alpha = Eigen::VectorXd::Zero(mesh_->num_faces());
  if (unknowns_.empty()) return alpha;
  const Eigen::VectorXd x = solver_->cholesky.solve(b_);
  for (std::size_t i = 0; i < unknowns_.size(); ++i) alpha[unknowns_[i]] = x[static_cast<Eigen::Index>(i)];
  return alpha;
}

Eigen::VectorXd FrameSmoother::solve_after(const Eigen::VectorXd& alpha, std::span<const MatchingChange> changes) {
  std::vector<int> rows;  // the unknowns whose b the changes touch
  std::vector<std::pair<int, double>> saved_theta;
  for (const MatchingChange& c : changes) {
    if (c.delta == 0 || mesh_->is_boundary_edge(c.edge)) continue;
    saved_theta.emplace_back(c.edge, theta_[c.edge]);
    for (int side = 0; side < 2; ++side)
      if (const int u = unknown_of_face_[static_cast<std::size_t>(mesh_->EF()(c.edge, side))]; u >= 0)
        rows.push_back(u);
  }
  if (rows.empty()) return alpha;
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  std::vector<double> before(rows.size()), delta(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) before[k] = b_[rows[k]];
  for (const MatchingChange& c : changes) change_matching(c.edge, c.delta);
  for (std::size_t k = 0; k < rows.size(); ++k) delta[k] = b_[rows[k]] - before[k], b_[rows[k]] = before[k];
  for (const MatchingChange& c : changes)
    if (c.delta != 0 && !mesh_->is_boundary_edge(c.edge)) matching_[c.edge] -= c.delta;
  for (auto it = saved_theta.rbegin(); it != saved_theta.rend(); ++it) theta_[it->first] = it->second;
  solver_->cholesky.prepare_sparse_solves();  // at the first call: a smoother never asked keeps its factor untouched
  const Eigen::VectorXd x = solver_->cholesky.solve_sparse(rows, delta);
  Eigen::VectorXd result = alpha;
  for (std::size_t i = 0; i < unknowns_.size(); ++i) result[unknowns_[i]] += x[static_cast<Eigen::Index>(i)];
  return result;
}

Eigen::VectorXd FrameSmoother::solve_system(const Eigen::VectorXd& r) const {
  Eigen::VectorXd rhs(num_unknowns()), x = Eigen::VectorXd::Zero(r.size());
  for (std::size_t i = 0; i < unknowns_.size(); ++i) rhs[static_cast<Eigen::Index>(i)] = r[unknowns_[i]];
  if (unknowns_.empty()) return x;
  const Eigen::VectorXd y = solver_->cholesky.solve(rhs);
  for (std::size_t i = 0; i < unknowns_.size(); ++i) x[unknowns_[i]] = y[static_cast<Eigen::Index>(i)];
  return x;
}

FrameField FrameSmoother::rotated(const Eigen::VectorXd& alpha) const {
  Eigen::VectorXcd X(X0_.size());
  for (Eigen::Index t = 0; t < X.size(); ++t) X[t] = std::polar(1.0, alpha[t]) * X0_[t];
  return make_cross_field(std::move(X), matching_);
}

double FrameSmoother::smoothing_energy(const Eigen::VectorXd& alpha) const {
  double E = 0;
  for (int e = 0; e < mesh_->num_edges(); ++e) {
    if (mesh_->is_boundary_edge(e)) continue;
    const double d = theta_[e] - alpha[mesh_->EF()(e, 0)] + alpha[mesh_->EF()(e, 1)];
    E += omega_[e] * d * d;
  }
  return E;
}

void FrameSmoother::set_alignment_targets(const Eigen::VectorXd& beta) {
  if (beta.size() != beta_.size()) throw std::invalid_argument("FrameSmoother: β must have one entry per face");
  for (std::size_t i = 0; i < unknowns_.size(); ++i) {
    const int t = unknowns_[i];
    // ∂/∂α_t of (1-λ) a_t (α_t - β_t)² puts (1-λ) a_t β_t into b_t.
    b_[static_cast<Eigen::Index>(i)] += (1 - lambda_) * align_[t] * (beta[t] - beta_[t]);
  }
  beta_ = beta;
}

double FrameSmoother::alignment_energy(const Eigen::VectorXd& alpha) const {
  return (align_.array() * (alpha - beta_).array().square()).sum();
}

}  // namespace quadcover
