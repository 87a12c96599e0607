#include "field/power_field.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "calculus/sparse_cholesky.h"
#include "field/matching.h"

namespace quadcover {

namespace {

// c = (d/|d|)^4, 1 for d = 0.
Complex powered_unit(Complex d) {
  const double r = std::abs(d);
  if (!(r > 0)) return 1.0;
  const Complex w = d / r, w2 = w * w;
  return w2 * w2;
}

void check(const Mesh& mesh, const PowerFieldProblem& p) {
  const int nf = mesh.num_faces();
  if (p.target.size() != nf || p.weight.size() != nf ||
      (!p.fixed.empty() && p.fixed.size() != static_cast<std::size_t>(nf)))
    throw std::invalid_argument("smooth_power_field: input sizes do not match the mesh");
  if (!(p.alignment >= 0)) throw std::invalid_argument("smooth_power_field: μ must be >= 0");
  if (nf > 0 && !(p.weight.minCoeff() >= 0))
    throw std::invalid_argument("smooth_power_field: alignment weights must be >= 0");
}

// A_M per connected component.
Eigen::VectorXd component_area(const Mesh& mesh) {
  Eigen::VectorXd area = Eigen::VectorXd::Zero(mesh.num_components());
  for (int t = 0; t < mesh.num_faces(); ++t) area[mesh.face_component()[t]] += mesh.face_areas()[t];
  return area;
}

// μ a_t A_t / A_M per face: the coefficient of |u_t - c_t|².
Eigen::VectorXd alignment_coefficients(const Mesh& mesh, const PowerFieldProblem& p) {
  const Eigen::VectorXd area = component_area(mesh);
  Eigen::VectorXd k(mesh.num_faces());
  for (int t = 0; t < mesh.num_faces(); ++t)
    k[t] = p.alignment * p.weight[t] * mesh.face_areas()[t] / area[mesh.face_component()[t]];
  return k;
}

// ρ_e^4: the transport of powered crosses from s = EF(e,0) to t = EF(e,1).
Complex powered_transport(const Mesh& mesh, int e) {
  const Complex r = mesh.edge_transport()[e], r2 = r * r;
  return r2 * r2;
}

// The faces held at u_t = c_t: the fixed ones plus the lowest-index face of every component without an anchor
// (E is rotation invariant there).
std::vector<char> held_faces(const Mesh& mesh, const PowerFieldProblem& problem, const Eigen::VectorXd& kappa) {
  const int nf = mesh.num_faces();
  std::vector<char> held(static_cast<std::size_t>(nf), 0);
  for (std::size_t t = 0; t < problem.fixed.size(); ++t) held[t] = problem.fixed[t];
  std::vector<char> anchored(static_cast<std::size_t>(mesh.num_components()), 0);
  for (int t = 0; t < nf; ++t)
    if (held[static_cast<std::size_t>(t)] || kappa[t] > 0)
      anchored[static_cast<std::size_t>(mesh.face_component()[t])] = 1;
  for (int t = 0; t < nf; ++t) {
    auto& a = anchored[static_cast<std::size_t>(mesh.face_component()[t])];
    if (!a) held[static_cast<std::size_t>(t)] = a = 1;
  }
  return held;
}

// ∇E = 0 as A x = b over the unknown faces: A Hermitian positive definite, the held faces' terms moved to b.
struct PowerSystem {
  std::vector<int> faces;  ///< face of each unknown
  Eigen::SparseMatrix<Complex> A;
  Eigen::VectorXcd b;
};

PowerSystem assemble_power_system(const Mesh& mesh, const std::vector<char>& held, const Eigen::VectorXd& kappa,
                                  const Eigen::VectorXcd& u) {
  const int nf = mesh.num_faces(), ne = mesh.num_edges();
  const Eigen::VectorXd omega = smoothing_edge_weights(mesh);
  PowerSystem sys;
  std::vector<int> unknown(static_cast<std::size_t>(nf), -1);
  for (int t = 0; t < nf; ++t)
    if (!held[static_cast<std::size_t>(t)]) {
      unknown[static_cast<std::size_t>(t)] = static_cast<int>(sys.faces.size());
      sys.faces.push_back(t);
    }
  const int n = static_cast<int>(sys.faces.size());
  std::vector<Eigen::Triplet<Complex>> entries;
  entries.reserve(static_cast<std::size_t>(n + 4 * ne));
  sys.b = Eigen::VectorXcd::Zero(n);
  for (int i = 0; i < n; ++i) {
    const int t = sys.faces[static_cast<std::size_t>(i)];
    if (kappa[t] > 0) {
      entries.emplace_back(i, i, kappa[t]);
      sys.b[i] += kappa[t] * u[t];
    }
  }
  for (int e = 0; e < ne; ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    const int fs = mesh.EF()(e, 0), ft = mesh.EF()(e, 1);
    const int s = unknown[static_cast<std::size_t>(fs)], t = unknown[static_cast<std::size_t>(ft)];
    const double w = omega[e];
    const Complex q = powered_transport(mesh, e);
    // ω|u_t - q u_s|²: rows t and s of the gradient are ω(u_t - q u_s) and ω(u_s - q̄ u_t).
    if (s >= 0) entries.emplace_back(s, s, w);
    if (t >= 0) entries.emplace_back(t, t, w);
    if (s >= 0 && t >= 0) {
      entries.emplace_back(t, s, -w * q);
      entries.emplace_back(s, t, -w * std::conj(q));
    } else if (t >= 0) {
      sys.b[t] += w * q * u[fs];
    } else if (s >= 0) {
      sys.b[s] += w * std::conj(q) * u[ft];
    }
  }
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, 0.0);  // the diagonal's pattern, for refactorize()
  sys.A.resize(n, n);
  sys.A.setFromTriplets(entries.begin(), entries.end());
  return sys;
}

// Majorize-minimize steps for the Ginzburg–Landau term from the linear solution x: (|u| - 1)² <= |u - u⁰/|u⁰||²,
// equal at u = u⁰. Returns the steps taken.
int ginzburg_landau_steps(const Mesh& mesh, const PowerFieldProblem& problem, PowerSystem& sys,
                          SparseCholesky<Complex>& cholesky, Eigen::VectorXcd& x) {
  const int n = static_cast<int>(sys.faces.size());
  const Eigen::VectorXd area = component_area(mesh);
  Eigen::VectorXd g(n);
  for (int i = 0; i < n; ++i) {
    const int t = sys.faces[static_cast<std::size_t>(i)];
    g[i] = problem.unit_weight * mesh.face_areas()[t] / area[mesh.face_component()[t]];
    sys.A.coeffRef(i, i) += g[i];
  }
  cholesky.refactorize(sys.A);
  Eigen::VectorXcd previous = x;
  int steps = 0;
  for (int k = 0; k < problem.iterations; ++k) {
    Eigen::VectorXcd rhs = sys.b;
    for (int i = 0; i < n; ++i)
      if (std::abs(x[i]) > 0) rhs[i] += g[i] * x[i] / std::abs(x[i]);
    x = cholesky.solve(rhs);
    ++steps;
    double moved = 0;
    for (int i = 0; i < n; ++i) moved = std::max(moved, std::abs(std::arg(x[i] * std::conj(previous[i]))));
    previous = x;
    if (moved < 1e-6) break;
  }
  return steps;
}

// X_t = (u_t/|u_t|)^{1/4}; at held faces the target itself, so that it lies exactly in the cross.
Eigen::VectorXcd first_frame_vectors(const PowerFieldProblem& problem, const PowerFieldResult& r) {
  const Eigen::Index nf = r.u.size();
  Eigen::VectorXcd X(nf);
  for (Eigen::Index t = 0; t < nf; ++t) {
    const Complex d = problem.target[t];
    if (r.held[static_cast<std::size_t>(t)] && std::abs(d) > 0)
      X[t] = d / std::abs(d);
    else
      X[t] = std::abs(r.u[t]) > 0 ? std::polar(1.0, 0.25 * std::arg(r.u[t])) : Complex(1.0);
  }
  return X;
}

}  // namespace

PowerFieldResult smooth_power_field(const Mesh& mesh, const PowerFieldProblem& problem) {
  check(mesh, problem);
  const int nf = mesh.num_faces();
  const Eigen::VectorXd kappa = alignment_coefficients(mesh, problem);
  PowerFieldResult r;
  r.held = held_faces(mesh, problem, kappa);
  r.u.resize(nf);
  for (int t = 0; t < nf; ++t) r.u[t] = powered_unit(problem.target[t]);
  PowerSystem sys = assemble_power_system(mesh, r.held, kappa, r.u);
  if (!sys.faces.empty()) {
    SparseCholesky<Complex> cholesky;
    cholesky.compute(sys.A, "field power fill");  // throws NumericalError if not positive definite
    Eigen::VectorXcd x = cholesky.solve(sys.b);
    if (problem.unit_weight > 0 && problem.iterations > 0)
      r.iterations = ginzburg_landau_steps(mesh, problem, sys, cholesky, x);
    for (std::size_t i = 0; i < sys.faces.size(); ++i) r.u[sys.faces[i]] = x[static_cast<Eigen::Index>(i)];
  }
  r.X = first_frame_vectors(problem, r);
  return r;
}

double power_field_energy(const Mesh& mesh, const PowerFieldProblem& problem, const Eigen::VectorXcd& u,
                          bool ginzburg_landau) {
  check(mesh, problem);
  const Eigen::VectorXd kappa = alignment_coefficients(mesh, problem);
  const Eigen::VectorXd omega = smoothing_edge_weights(mesh);
  double E = 0;
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (!mesh.is_boundary_edge(e))
      E += omega[e] * std::norm(u[mesh.EF()(e, 1)] - powered_transport(mesh, e) * u[mesh.EF()(e, 0)]);
  for (int t = 0; t < mesh.num_faces(); ++t) E += kappa[t] * std::norm(u[t] - powered_unit(problem.target[t]));
  if (ginzburg_landau) {
    const Eigen::VectorXd area = component_area(mesh);
    for (int t = 0; t < mesh.num_faces(); ++t) {
      const double d = std::abs(u[t]) - 1;
      E += problem.unit_weight * mesh.face_areas()[t] / area[mesh.face_component()[t]] * d * d;
    }
  }
  return E;
}

}  // namespace quadcover
