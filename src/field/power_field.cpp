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

}  // namespace

PowerFieldResult smooth_power_field(const Mesh& mesh, const PowerFieldProblem& problem) {
  check(mesh, problem);
  const int nf = mesh.num_faces(), ne = mesh.num_edges();
  const Eigen::VectorXd kappa = alignment_coefficients(mesh, problem);
  const Eigen::VectorXd omega = smoothing_edge_weights(mesh);

  PowerFieldResult r;
  r.held.assign(static_cast<std::size_t>(nf), 0);
  for (std::size_t t = 0; t < problem.fixed.size(); ++t) r.held[t] = problem.fixed[t];
  // Hold the lowest-index face of every component without an anchor (E is rotation invariant there).
  std::vector<char> anchored(static_cast<std::size_t>(mesh.num_components()), 0);
  for (int t = 0; t < nf; ++t)
    if (r.held[static_cast<std::size_t>(t)] || kappa[t] > 0)
      anchored[static_cast<std::size_t>(mesh.face_component()[t])] = 1;
  for (int t = 0; t < nf; ++t) {
    auto& a = anchored[static_cast<std::size_t>(mesh.face_component()[t])];
    if (!a) r.held[static_cast<std::size_t>(t)] = a = 1;
  }

  std::vector<int> unknown(static_cast<std::size_t>(nf), -1), faces;
  for (int t = 0; t < nf; ++t)
    if (!r.held[static_cast<std::size_t>(t)]) {
      unknown[static_cast<std::size_t>(t)] = static_cast<int>(faces.size());
      faces.push_back(t);
    }
  const int n = static_cast<int>(faces.size());

  r.u.resize(nf);
  for (int t = 0; t < nf; ++t) r.u[t] = powered_unit(problem.target[t]);

  // ∇E = 0: A u = b with A Hermitian positive definite; held faces move to b.
  std::vector<Eigen::Triplet<Complex>> entries;
  entries.reserve(static_cast<std::size_t>(n + 4 * ne));
  Eigen::VectorXcd b = Eigen::VectorXcd::Zero(n);
  for (int i = 0; i < n; ++i) {
    const int t = faces[static_cast<std::size_t>(i)];
    if (kappa[t] > 0) {
      entries.emplace_back(i, i, kappa[t]);
      b[i] += kappa[t] * r.u[t];
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
      b[t] += w * q * r.u[fs];
    } else if (s >= 0) {
      b[s] += w * std::conj(q) * r.u[ft];
    }
  }
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, 0.0);  // the diagonal's pattern, for refactorize()
  if (n > 0) {
    Eigen::SparseMatrix<Complex> A(n, n);
    A.setFromTriplets(entries.begin(), entries.end());
    SparseCholesky<Complex> cholesky;
    cholesky.compute(A, "field power fill");  // throws NumericalError if not positive definite
    Eigen::VectorXcd x = cholesky.solve(b);
    if (problem.unit_weight > 0 && problem.iterations > 0) {
      // Majorize-minimize for the Ginzburg–Landau term: (|u| - 1)² <= |u - u⁰/|u⁰||², equal at u = u⁰.
      const Eigen::VectorXd area = component_area(mesh);
      Eigen::VectorXd g(n);
      for (int i = 0; i < n; ++i) {
        const int t = faces[static_cast<std::size_t>(i)];
        g[i] = problem.unit_weight * mesh.face_areas()[t] / area[mesh.face_component()[t]];
        A.coeffRef(i, i) += g[i];
      }
      cholesky.refactorize(A);
      Eigen::VectorXcd previous = x;
      for (int k = 0; k < problem.iterations; ++k) {
        Eigen::VectorXcd rhs = b;
        for (int i = 0; i < n; ++i)
          if (std::abs(x[i]) > 0) rhs[i] += g[i] * x[i] / std::abs(x[i]);
        x = cholesky.solve(rhs);
        ++r.iterations;
        double moved = 0;
        for (int i = 0; i < n; ++i) moved = std::max(moved, std::abs(std::arg(x[i] * std::conj(previous[i]))));
        previous = x;
        if (moved < 1e-6) break;
      }
    }
    for (int i = 0; i < n; ++i) r.u[faces[static_cast<std::size_t>(i)]] = x[i];
  }

  // X_t = (u_t/|u_t|)^{1/4}; at held faces the target itself, so that it lies exactly in the cross.
  r.X.resize(nf);
  for (int t = 0; t < nf; ++t) {
    const Complex d = problem.target[t];
    if (r.held[static_cast<std::size_t>(t)] && std::abs(d) > 0)
      r.X[t] = d / std::abs(d);
    else
      r.X[t] = std::abs(r.u[t]) > 0 ? std::polar(1.0, 0.25 * std::arg(r.u[t])) : Complex(1.0);
  }
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
