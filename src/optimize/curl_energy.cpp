#include "optimize/curl_energy.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/errors.h"
#include "common/quarter_turn.h"
#include "common/seconds_since.h"
#include "cover/complex_stiffness.h"

namespace quadcover {

CurlEnergy::CurlEnergy(const Mesh& mesh, FrameSmoother& smoother, const CurlEnergyOptions& options)
    : mesh_(&mesh), smoother_(&smoother), options_(options) {
  recompute_from_scratch();
}

CurlEnergy::~CurlEnergy() = default;
CurlEnergy::CurlEnergy(CurlEnergy&&) noexcept = default;

namespace {

// 𝔏̄* + εI with v = 0 on boundary edges (1.2.4), as parameterize() solves it: a boundary edge's row and column keep
// only their diagonal and its right-hand side is 0 (rhs()), so v_b = 0 and it adds nothing to E_D. Its pattern
// depends on the mesh only.
Eigen::SparseMatrix<Complex> shifted_curl_stiffness(const Mesh& mesh, const Eigen::VectorXi& matching,
                                                    double diagonal_shift) {
  Eigen::SparseMatrix<Complex> A = complex_nonconforming_stiffness(mesh, matching);
  A.prune([&](Eigen::Index i, Eigen::Index j, const Complex&) {
    return i == j || (!mesh.is_boundary_edge(static_cast<int>(i)) && !mesh.is_boundary_edge(static_cast<int>(j)));
  });
  double mean = 0;
  for (int i = 0; i < A.rows(); ++i) mean += std::abs(A.coeff(i, i));
  mean /= std::max<Eigen::Index>(1, A.rows());
  Eigen::SparseMatrix<Complex> I(A.rows(), A.cols());
  I.setIdentity();
  return A + (diagonal_shift * mean) * I;
}

}  // namespace

std::vector<int> order_curl_energy_ahead(const Mesh& mesh) {
  return UpdatableCholesky::order_ahead(shifted_curl_stiffness(mesh, Eigen::VectorXi::Zero(mesh.num_edges()), 1.0));
}

Eigen::SparseMatrix<Complex> CurlEnergy::shifted_stiffness() const {
  return shifted_curl_stiffness(*mesh_, smoother_->matching(), options_.diagonal_shift);
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
  solution_valid_ = false;
  ++rebuilds_;
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
  if (delta == 0 || mesh_->is_boundary_edge(e)) return StarChange{e, {}};
  return star_change(e, field_.matching[e] + delta, [&](int f, int k) { return mu_(f, k); });
}

double CurlEnergy::curvature(int e) const {
  if (mesh_->is_boundary_edge(e)) return 0;
  return smoother_->curvature()[e] - alpha_[mesh_->EF()(e, 0)] + alpha_[mesh_->EF()(e, 1)];
}

double CurlEnergy::evaluate(std::span<const MatchingChange> changes) {
  ++timings_.evaluations;
  auto t0 = SteadyClock::now();
  pending_.assign(changes.begin(), changes.end());
  pending_valid_ = false;
  // min E(α) with the new matching (5.2.2), from α and the changed entries of b; the smoother stays as it is.
  pending_alpha_ = smoother_->solve_after(alpha_, changes);  // from the few entries of b the changes move
  timings_.smoothing += seconds_since(t0);
  // Star changes one edge at a time (a path may cross the same face twice: layers are updated as we go).
  t0 = SteadyClock::now();
  trial_.reset();
  bool ok = true;
  std::vector<std::tuple<int, int, int>> saved;  // (face, slot, old μ)
  for (const auto& c : changes) {
    if (mesh_->is_boundary_edge(c.edge) || c.delta == 0) continue;
    const StarChange star = stiffness_change(c.edge, c.delta);
    ok = ok && trial_.add_star_change(factor_, star);
    const auto [g, a] = changed_slot(c.edge);
    saved.emplace_back(g, a, mu_(g, a));
    field_.matching[c.edge] += c.delta;
    mu_(g, a) = layer_after(c.edge, field_.matching[c.edge]);
  }
  timings_.update += seconds_since(t0);
  t0 = SteadyClock::now();
  const Eigen::VectorXcd b = rhs(pending_alpha_);  // -curl* of the re-smoothed field with the new layers
  timings_.curl += seconds_since(t0);
  for (auto it = saved.rbegin(); it != saved.rend(); ++it) mu_(std::get<0>(*it), std::get<1>(*it)) = std::get<2>(*it);
  for (const auto& c : changes)
    if (!mesh_->is_boundary_edge(c.edge)) field_.matching[c.edge] -= c.delta;
  if (!ok) return std::numeric_limits<double>::infinity();
  t0 = SteadyClock::now();
  const double e = trial_.evaluate_full(factor_, b);
  timings_.solve += seconds_since(t0);
  pending_valid_ = true;
  return e;
}

void CurlEnergy::commit() {
  if (!pending_valid_) throw NumericalError("curl reduction", "commit without a valid evaluation");
  const auto t_commit = SteadyClock::now();
  for (const auto& c : pending_) {
    if (mesh_->is_boundary_edge(c.edge) || c.delta == 0) continue;
    smoother_->change_matching(c.edge, c.delta);
    const auto [g, a] = changed_slot(c.edge);
    mu_(g, a) = layer_after(c.edge, smoother_->matching()[c.edge]);
  }
  alpha_ = pending_alpha_;
  field_ = smoother_->rotated(alpha_);
  trial_.commit(factor_);
  trial_.reset();
  pending_valid_ = false;
  solution_valid_ = false;
  ++commits_;
  timings_.commit += seconds_since(t_commit);
}

// One face's term of -curl* (3.3) at its edge k for the rotated frame X = e^{iα}X⁰_f (Y = iX) on layer μ:
// conj(i^μ) ⟨Z_f, e⟩ with ⟨Z, e⟩ = ⟨X, e⟩ + i⟨Y, e⟩ (the sum of cover/complex_stiffness.cpp, with cached edge
// vectors and layers instead of a global layer recomputation).
Complex CurlEnergy::term(int f, int k, Complex X, int mu) const {
  const Complex ce = std::conj(edge_vec_(f, k));
  return product(ipow(-mu), Complex(product(ce, X).real(), product(ce, Complex(-X.imag(), X.real())).real()));
}

Complex CurlEnergy::contribution(int f, int k, double alpha, int mu) const {
  return term(f, k, rotated_frame(f, alpha), mu);
}

// -curl* of the field e^{iα}X⁰ with the current layers: one rotation per face (not one per face edge). The face
// terms are made on both cores; each edge then sums its two in face order, as one loop over the faces would.
Eigen::VectorXcd CurlEnergy::rhs(const Eigen::VectorXd& alpha) const {
  Eigen::MatrixX3cd terms(mesh_->num_faces(), 3);
  tbb::parallel_for(tbb::blocked_range<int>(0, mesh_->num_faces(), 4096), [&](const tbb::blocked_range<int>& faces) {
    for (int f = faces.begin(); f < faces.end(); ++f) {
      const Complex X = rotated_frame(f, alpha[f]);
      for (int k = 0; k < 3; ++k) terms(f, k) = term(f, k, X, mu_(f, k));
    }
  });
  Eigen::VectorXcd b = Eigen::VectorXcd::Zero(mesh_->num_edges());
  for (int f = 0; f < mesh_->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) b[mesh_->FE()(f, k)] += terms(f, k);
  for (int e = 0; e < mesh_->num_edges(); ++e)
    if (mesh_->is_boundary_edge(e)) b[e] = 0;  // v = 0 there (shifted_stiffness)
  return b;
}

const Eigen::VectorXcd& CurlEnergy::solution() const {
  if (!solution_valid_) {
    const auto t0 = SteadyClock::now();
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

}  // namespace quadcover
