// Untangling and injective polish of the final map (Garanzha et al. 2021; Smith & Schaefer 2015). See untangle.h.
#include "param/untangle.h"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "calculus/sparse_cholesky.h"
#include "common/errors.h"
#include "common/seconds_since.h"
#include "mesh/vertex_rings.h"
#include "param/isotropic_projection.h"
#include "param/region_folds.h"
#include "param/seams.h"

namespace quadcover {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// χ(D, ε) = (D + √(ε² + D²)) / 2, written without cancellation for D < 0; s = √(ε² + D²).
double chi(double D, double eps, double& s) {
  const double m = std::max(eps, std::abs(D));  // √(ε² + D²): std::hypot only where the squares could leave range
  s = m > 1e-100 && m < 1e100 ? std::sqrt(eps * eps + D * D) : std::hypot(eps, D);
  return D >= 0 ? 0.5 * (D + s) : 0.5 * eps * eps / (s - D);
}

/// Per face: vec J = J0 + Dm · x_loc, with x_loc the six real components (x, y of u at its three corners).
struct FaceMap {
  Eigen::Vector4d J0;
  Eigen::Matrix<double, 4, 6> Dm;
  std::array<int, 6> var;  ///< global component index (x_p: p, y_p: #V + p)
  double area = 0;
};

/// The reference T of face f (rows Z⁰, Z¹ in the face's frame), or its RMS length times the identity where Z is
/// degenerate or mirrored.
Eigen::Matrix2d reference(const FramePairs& Z, int f) {
  Eigen::Matrix2d T;
  T << Z(f, 0).real(), Z(f, 0).imag(), Z(f, 1).real(), Z(f, 1).imag();
  const double n2 = T.squaredNorm();
  if (T.determinant() > 1e-6 * n2 && std::isfinite(n2)) return T;
  const double r = std::sqrt(0.5 * n2);
  return (r > 0 && std::isfinite(r) ? r : 1.0) * Eigen::Matrix2d::Identity();
}

std::vector<FaceMap> face_maps(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                               const FramePairs& Z) {
  const int nf = mesh.num_faces(), nv = mesh.num_vertices();
  std::vector<FaceMap> maps(static_cast<std::size_t>(nf));
  tbb::parallel_for(0, nf, [&](int f) {
    FaceMap& m = maps[f];
    m.area = mesh.face_areas()[f];
    const Eigen::Matrix2d Tinv = reference(Z, f).inverse();
    const double A2 = 2 * m.area;
    Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
    for (int c = 0; c < 3; ++c) {
      const Complex g = Complex(0, 1) * mesh.edge_vector_local(f, c) / A2;  // ∇φ_c = J e_c / 2A
      const Eigen::RowVector2d gr(g.real(), g.imag());
      J.row(0) += base(f, c).real() * gr;
      J.row(1) += base(f, c).imag() * gr;
      const int p = mesh.F()(f, c);
      for (int k = 0; k < 2; ++k) {
        m.var[2 * c + k] = k * nv + p;
        // φ_c = base_c − i^λ (x + iy): ∂φ_c/∂x = −i^λ, ∂φ_c/∂y = −i^{λ+1} (0 at branch points).
        const Complex w = layers.branch[p] ? Complex(0) : -ipow(layers.layer(f, c) + k);
        Eigen::Matrix2d dJ;
        dJ.row(0) = w.real() * gr;
        dJ.row(1) = w.imag() * gr;
        dJ = dJ * Tinv;
        m.Dm.col(2 * c + k) << dJ(0, 0), dJ(0, 1), dJ(1, 0), dJ(1, 1);
      }
    }
    J = J * Tinv;
    m.J0 << J(0, 0), J(0, 1), J(1, 0), J(1, 1);
  });
  return maps;
}

Eigen::Matrix<double, 6, 1> local(const FaceMap& m, const Eigen::VectorXd& X);

/// True if the fixed components hold the determinant of the face at ≤ 0 whatever the free ones do: all six fixed, or
/// det ≡ 0 (two corners pinned to one point, e.g. adjacent branch points on one integer point; three on one fixed
/// iso-line). The determinant is a quadratic in the free components: it vanishes identically iff it vanishes at the
/// current point and at a few others (fixed pseudo-random offsets of one grid unit).
bool stuck_face(const FaceMap& m, const std::vector<char>& fixed, const Eigen::VectorXd& X) {
  static constexpr double offsets[3][6] = {{0.71, -0.33, 0.52, 0.93, -0.61, 0.24},
                                           {-0.45, 0.87, -0.12, 0.38, 0.66, -0.91},
                                           {0.29, 0.55, -0.83, -0.47, 0.18, 0.74}};
  const Eigen::Matrix<double, 6, 1> x = local(m, X);
  const auto det = [&](const Eigen::Matrix<double, 6, 1>& y) {
    const Eigen::Vector4d J = m.J0 + m.Dm * y;
    return J[0] * J[3] - J[1] * J[2];
  };
  bool any_free = false;
  for (int k = 0; k < 6; ++k) any_free = any_free || (!fixed[m.var[k]] && m.Dm.col(k).squaredNorm() > 0);
  if (!any_free) return det(x) <= 0;
  bool zero = std::abs(det(x)) <= 1e-12 * (1 + (m.J0 + m.Dm * x).squaredNorm());
  for (int s = 0; s < 3 && zero; ++s) {
    Eigen::Matrix<double, 6, 1> y = x;
    for (int k = 0; k < 6; ++k)
      if (!fixed[m.var[k]]) y[k] += offsets[s][k];
    zero = std::abs(det(y)) <= 1e-12 * (1 + (m.J0 + m.Dm * y).squaredNorm());
  }
  return zero;
}

/// Releases, per stuck face, the `releasable` components of the first corner whose release unsticks it (a curve
/// constraint given up at one vertex); returns the released vertices.
std::vector<int> release_corners(const std::vector<FaceMap>& maps, const std::vector<char>& releasable,
                                 const Eigen::VectorXd& X, std::vector<char>& fixed) {
  const int nv = static_cast<int>(fixed.size() / 2);
  std::vector<int> released;
  for (const FaceMap& m : maps) {
    if (!stuck_face(m, fixed, X)) continue;
    for (int c = 0; c < 3; ++c) {
      const int p = m.var[2 * c];
      if (!releasable[p] && !releasable[nv + p]) continue;
      std::vector<char> trial = fixed;
      for (const int i : {p, nv + p})
        if (releasable[i]) trial[i] = 0;
      if (stuck_face(m, trial, X)) continue;
      fixed.swap(trial);
      released.push_back(p);
      break;
    }
  }
  std::sort(released.begin(), released.end());
  return released;
}

Eigen::Matrix<double, 6, 1> local(const FaceMap& m, const Eigen::VectorXd& X) {
  Eigen::Matrix<double, 6, 1> x;
  for (int k = 0; k < 6; ++k) x[k] = X[m.var[k]];
  return x;
}

Eigen::Matrix2d as_matrix(const Eigen::Vector4d& v) { return (Eigen::Matrix2d() << v[0], v[1], v[2], v[3]).finished(); }

/// The free components and the Hessian's fixed pattern: per face, the value index of each (k, l) pair (−1 if
/// either is fixed) and of each free component's diagonal.
struct Pattern {
  std::vector<int> free_id;  ///< per global component: its free index or −1
  int nfree = 0;
  Eigen::SparseMatrix<double> H;
  std::vector<std::array<int, 36>> slot;
  std::vector<int> diagonal;
};

Pattern build_pattern(const std::vector<FaceMap>& maps, const std::vector<char>& fixed) {
  Pattern P;
  P.free_id.assign(fixed.size(), -1);
  for (std::size_t i = 0; i < fixed.size(); ++i)
    if (!fixed[i]) P.free_id[i] = P.nfree++;
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(maps.size() * 36 + static_cast<std::size_t>(P.nfree));
  for (int i = 0; i < P.nfree; ++i) trip.emplace_back(i, i, 1.0);
  for (const FaceMap& m : maps)
    for (int k = 0; k < 6; ++k)
      for (int l = 0; l < 6; ++l) {
        const int a = P.free_id[m.var[k]], b = P.free_id[m.var[l]];
        if (a >= 0 && b >= 0) trip.emplace_back(a, b, 1.0);
      }
  P.H.resize(P.nfree, P.nfree);
  P.H.setFromTriplets(trip.begin(), trip.end());
  P.H.makeCompressed();
  const double* v0 = P.H.valuePtr();
  P.slot.resize(maps.size());
  for (std::size_t f = 0; f < maps.size(); ++f)
    for (int k = 0; k < 6; ++k)
      for (int l = 0; l < 6; ++l) {
        const int a = P.free_id[maps[f].var[k]], b = P.free_id[maps[f].var[l]];
        P.slot[f][6 * k + l] = a >= 0 && b >= 0 ? static_cast<int>(&P.H.coeffRef(a, b) - v0) : -1;
      }
  P.diagonal.resize(static_cast<std::size_t>(P.nfree));
  for (int i = 0; i < P.nfree; ++i) P.diagonal[i] = static_cast<int>(&P.H.coeffRef(i, i) - v0);
  return P;
}

/// The energy F_ε and the Jacobian determinants of the map at X.
class Energy {
 public:
  Energy(const std::vector<FaceMap>& maps, double lambda) : maps_(maps), lambda_(lambda) {}

  /// Σ_t A_t f_ε(J_t) along X + t·ΔX (per-face ΔJ precomputed by direction()).
  double value(const Eigen::VectorXd& X, double eps, double t = 0) const {
    const int nf = static_cast<int>(maps_.size());
    std::vector<double> e(static_cast<std::size_t>(nf));
    tbb::parallel_for(0, nf, [&](int f) {
      Eigen::Vector4d J = maps_[f].J0 + maps_[f].Dm * local(maps_[f], X);
      if (t != 0) J += t * dJ_[f];
      e[f] = maps_[f].area > 0 ? maps_[f].area * untangle_density(as_matrix(J), eps, lambda_) : 0.0;
    });
    double s = 0;
    for (double v : e) s += v;  // sequential: the same sum for every thread count
    return s;
  }
  double min_det(const Eigen::VectorXd& X) const {
    double d = kInf;
    for (const FaceMap& m : maps_)
      if (m.area > 0) d = std::min(d, as_matrix(m.J0 + m.Dm * local(m, X)).determinant());
    return d;
  }
  /// Stores the per-face ΔJ of the direction ΔX (full 2·#V vector, 0 on fixed components).
  void direction(const Eigen::VectorXd& dX) {
    dJ_.resize(maps_.size());
    for (std::size_t f = 0; f < maps_.size(); ++f) dJ_[f] = maps_[f].Dm * local(maps_[f], dX);
  }
  /// The largest t ≤ 1 with det J_t > 0 on every face along X + t·ΔX, times `margin` if it is below 1.
  double injective_step(const Eigen::VectorXd& X, double margin) const {
    double tmax = 1;
    for (std::size_t f = 0; f < maps_.size(); ++f) {
      if (!(maps_[f].area > 0)) continue;
      const Eigen::Vector4d J = maps_[f].J0 + maps_[f].Dm * local(maps_[f], X), K = dJ_[f];
      // det(J + tK) = d0 + d1 t + d2 t²
      const double d0 = J[0] * J[3] - J[1] * J[2], d2 = K[0] * K[3] - K[1] * K[2];
      const double d1 = J[0] * K[3] + J[3] * K[0] - J[1] * K[2] - J[2] * K[1];
      double root = kInf;
      if (std::abs(d2) <= 1e-14 * (std::abs(d1) + std::abs(d0))) {
        if (d1 < 0) root = -d0 / d1;
      } else {
        const double disc = d1 * d1 - 4 * d2 * d0;
        if (disc >= 0) {
          const double q = -0.5 * (d1 + std::copysign(std::sqrt(disc), d1));
          for (const double r : {q / d2, d0 / q})
            if (r > 0) root = std::min(root, r);
        }
      }
      if (root < tmax / margin) tmax = margin * root;
    }
    return tmax;
  }
  const std::vector<FaceMap>& maps() const { return maps_; }
  double lambda() const { return lambda_; }

 private:
  const std::vector<FaceMap>& maps_;
  double lambda_;
  std::vector<Eigen::Vector4d> dJ_;
};

/// One projected Newton step on F_ε (ε = 0: the barrier, line search capped before the first inversion).
/// Returns false if no step lowered the energy.
bool newton_step(Energy& energy, Pattern& P, SparseCholesky<double>& chol, double eps, Eigen::VectorXd& X) {
  const std::vector<FaceMap>& maps = energy.maps();
  const int nf = static_cast<int>(maps.size());
  std::vector<Eigen::Matrix<double, 6, 1>> g6(static_cast<std::size_t>(nf));
  std::vector<Eigen::Matrix<double, 6, 6>> H6(static_cast<std::size_t>(nf));
  tbb::parallel_for(0, nf, [&](int f) {
    const FaceMap& m = maps[f];
    if (!(m.area > 0)) {
      g6[f].setZero();
      H6[f].setZero();
      return;
    }
    const Eigen::Vector4d J = m.J0 + m.Dm * local(m, X);
    Eigen::Vector4d g;
    Eigen::Matrix4d H;
    untangle_density(as_matrix(J), eps, energy.lambda(), &g, &H);
    g6[f] = m.area * m.Dm.transpose() * g;
    if (Eigen::LLT<Eigen::Matrix4d>(H).info() == Eigen::Success) {  // positive definite: the projection is H
      H6[f] = m.area * m.Dm.transpose() * H * m.Dm;
      return;
    }
    H6[f] = m.area * m.Dm.transpose() * project_isotropic_hessian(as_matrix(J), H) * m.Dm;
  });
  Eigen::VectorXd grad = Eigen::VectorXd::Zero(P.nfree);
  double* val = P.H.valuePtr();
  std::fill(val, val + P.H.nonZeros(), 0.0);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 6; ++k) {
      const int a = P.free_id[maps[f].var[k]];
      if (a < 0) continue;
      grad[a] += g6[f][k];
      for (int l = 0; l < 6; ++l)
        if (P.slot[f][6 * k + l] >= 0) val[P.slot[f][6 * k + l]] += H6[f](k, l);
    }
  if (!grad.allFinite()) return false;
  // Levenberg-Marquardt shift μ·I, raised until the projected Hessian is definite (its zero modes: faces whose
  // projected Hessian vanishes).
  double mean_diag = 0;
  for (int i : P.diagonal) mean_diag += val[i];
  mean_diag = P.nfree ? mean_diag / P.nfree : 1;
  double mu = 1e-9 * mean_diag;
  Eigen::VectorXd step;
  for (int attempt = 0;; ++attempt) {
    for (int i : P.diagonal) val[i] += mu;
    try {
      chol.factorize(P.H, "untangling (projected Newton)");
      step = -chol.solve(grad);
      break;
    } catch (const NumericalError&) {
      if (attempt == 8) throw;
      for (int i : P.diagonal) val[i] -= mu;
      mu *= 100;
    }
  }
  Eigen::VectorXd dX = Eigen::VectorXd::Zero(X.size());
  for (std::size_t i = 0; i < P.free_id.size(); ++i)
    if (P.free_id[i] >= 0) dX[i] = step[P.free_id[i]];
  energy.direction(dX);
  const double e0 = energy.value(X, eps), slope = grad.dot(step);
  if (!(slope < 0)) return false;
  double t = eps == 0 ? energy.injective_step(X, 0.9) : 1.0;
  for (int k = 0; k < 40; ++k, t *= 0.5) {
    const double e = energy.value(X, eps, t);
    if (e <= e0 + 1e-4 * t * slope) {
      X += t * dX;
      return true;
    }
  }
  return false;
}

/// The unknowns X = (Re u, Im u) of the untangler for a correction u, and back.
Eigen::VectorXd stacked(const Eigen::VectorXcd& u) {
  return (Eigen::VectorXd(2 * u.size()) << u.real(), u.imag()).finished();
}
Eigen::VectorXcd unstacked(const Eigen::VectorXd& X) {
  const Eigen::Index nv = X.size() / 2;
  Eigen::VectorXcd u(nv);
  for (Eigen::Index p = 0; p < nv; ++p) u[p] = Complex(X[p], X[nv + p]);
  return u;
}

Eigen::MatrixX3cd map_of(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                         const Eigen::VectorXd& X) {
  return base - layered_values(mesh, layers, unstacked(X));
}

/// The untangling and the polish on the faces with a component free in `region_fixed` (its pattern analysed once).
/// `remaining` counts the faces that still have to become positive; the run stops when none do, after
/// options.max_iterations ε rounds, or after options.patience rounds without fewer of them.
void untangle_region(const std::vector<FaceMap>& all, const std::vector<char>& region_fixed,
                     const std::function<int(const Eigen::VectorXd&)>& remaining, const UntangleOptions& options,
                     ProgressSink& progress, Eigen::VectorXd& X, ParamDiagnostics::Untangling& result) {
  std::vector<FaceMap> maps;
  for (const FaceMap& m : all) {
    bool moves = false;
    for (int k = 0; k < 6; ++k) moves = moves || !region_fixed[m.var[k]];
    if (moves && m.area > 0) maps.push_back(m);
  }
  if (maps.empty()) return;
  Energy energy(maps, options.area_weight);
  Pattern P = build_pattern(maps, region_fixed);
  SparseCholesky<double> chol;
  // Untangling (Garanzha et al. 2021): ε from the smallest determinant, then σ = max(1 − E/E_prev, 0.1),
  // μ = (1 − σ) χ(D_min, ε), ε ← 2√(μ(μ − D_min)) while D_min < μ (else 1e-10).
  double dmin = energy.min_det(X);
  double eps = std::sqrt(1e-12 + 0.04 * std::pow(std::min(dmin, 0.0), 2));
  int best = remaining(X), since_better = 0;
  Eigen::VectorXd best_X = X;
  bool injective = best == 0 && dmin > 0;
  for (int it = 0;
       it < options.max_iterations && !injective && since_better < options.patience && !progress.cancelled(); ++it) {
    const double e_prev = energy.value(X, eps);
    newton_step(energy, P, chol, eps, X);
    ++result.iterations;
    const double e = energy.value(X, eps);
    const double sigma = std::max(1 - e / e_prev, 0.1);
    dmin = energy.min_det(X);
    double s;
    const double mu = (1 - sigma) * chi(dmin, eps, s);
    eps = dmin < mu ? 2 * std::sqrt(mu * (mu - dmin)) : 1e-10;
    const int now = remaining(X);
    injective = dmin > 0 && now == 0;
    if (now < best)
      best = now, since_better = 0, best_X = X;
    else
      ++since_better;
  }
  if (!injective) {
    X = best_X;  // the fewest folds seen
    return;
  }
  // Injective polish on the barrier F_0.
  for (int it = 0; it < options.polish_iterations && !progress.cancelled(); ++it) {
    const double e_prev = energy.value(X, 0);
    if (!newton_step(energy, P, chol, 0, X)) break;
    ++result.polish_iterations;
    if (e_prev - energy.value(X, 0) < options.tolerance * e_prev) break;
  }
}

}  // namespace

double untangle_density(const Eigen::Matrix2d& J, double eps, double lambda, Eigen::Vector4d* gradient,
                        Eigen::Matrix4d* hessian) {
  const double a = J(0, 0), b = J(0, 1), c = J(1, 0), d = J(1, 1);
  const double D = a * d - b * c;
  if (eps == 0 && D <= 0) {
    if (gradient) gradient->setConstant(kInf);
    if (hessian) hessian->setZero();
    return kInf;
  }
  double s;
  const double x = chi(D, eps, s);
  const double N = a * a + b * b + c * c + d * d + lambda * (D * D + 1);
  const double f = N / x;
  if (!gradient && !hessian) return f;
  const double x1 = x / s;                          // χ'
  const double x2 = 0.5 * eps * eps / (s * s * s);  // χ''
  const Eigen::Vector4d v(a, b, c, d), gD(d, -c, -b, a);
  const Eigen::Vector4d gN = 2 * v + 2 * lambda * D * gD;
  if (gradient) *gradient = gN / x - N * x1 / (x * x) * gD;
  if (hessian) {
    Eigen::Matrix4d HD = Eigen::Matrix4d::Zero();
    HD(0, 3) = HD(3, 0) = 1;
    HD(1, 2) = HD(2, 1) = -1;
    const Eigen::Matrix4d HN = 2 * Eigen::Matrix4d::Identity() + 2 * lambda * (gD * gD.transpose() + D * HD);
    *hessian = HN / x - x1 / (x * x) * (gN * gD.transpose() + gD * gN.transpose()) +
               N * (2 * x1 * x1 / (x * x * x) - x2 / (x * x)) * gD * gD.transpose() - N * x1 / (x * x) * HD;
  }
  return f;
}

std::vector<char> untangle_fixed_components(const Mesh& mesh, const VertexLayers& layers,
                                            const std::vector<int>& pinned, const std::vector<char>& fixed_components) {
  const int nv = mesh.num_vertices();
  std::vector<char> fixed(static_cast<std::size_t>(2 * nv), 0);
  if (!fixed_components.empty())
    for (int i = 0; i < 2 * nv; ++i) fixed[i] = fixed_components[i];
  std::vector<char> used(static_cast<std::size_t>(nv), 0);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) used[mesh.F()(f, c)] = 1;
  for (int p = 0; p < nv; ++p)
    if (layers.branch[p] || !used[p]) fixed[p] = fixed[nv + p] = 1;
  for (int p : pinned) fixed[p] = fixed[nv + p] = 1;
  return fixed;
}

std::vector<int> release_stuck_corners(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                                       const FramePairs& Z, std::vector<char>& fixed,
                                       const std::vector<char>& releasable) {
  return release_corners(face_maps(mesh, layers, base, Z), releasable,
                         Eigen::VectorXd::Zero(2 * mesh.num_vertices()), fixed);
}

Eigen::VectorXcd untangle_map(const Mesh& mesh, const HarmonicCorrection& correction, const Eigen::MatrixX3cd& base,
                              const FramePairs& Z, const std::vector<char>& fixed, const Eigen::VectorXcd& u0,
                              const UntangleOptions& options, ProgressSink& progress,
                              ParamDiagnostics::Untangling& result, const std::vector<char>& releasable) {
  return untangle_map(mesh, correction.layers(), base, Z, fixed, u0, options, progress, result, releasable);
}

Eigen::VectorXcd untangle_map(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                              const FramePairs& Z, const std::vector<char>& fixed_in, const Eigen::VectorXcd& u0,
                              const UntangleOptions& options, ProgressSink& progress,
                              ParamDiagnostics::Untangling& result, const std::vector<char>& releasable) {
  const auto start = std::chrono::steady_clock::now();
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  if (static_cast<int>(fixed_in.size()) != 2 * nv || u0.size() != nv ||
      (!releasable.empty() && static_cast<int>(releasable.size()) != 2 * nv))
    throw InputError("", 0, "untangle_map: the fixed components or u0 do not match the mesh");
  result = {};
  Eigen::VectorXd X = stacked(u0);
  const int before = flipped_triangles(mesh, map_of(mesh, layers, base, X)).non_positive;
  result.non_positive_before = result.non_positive_after = before;
  if (!options.enabled || before == 0) return u0;

  std::vector<FaceMap> maps = face_maps(mesh, layers, base, Z);
  std::vector<char> fixed = fixed_in;
  if (options.release_curve_corners && !releasable.empty())
    result.released_vertices = release_corners(maps, releasable, X, fixed);
  // Faces the subspace holds non-positive are reported and left out of the energy (they would only pull at their
  // free corners); the others must end positive.
  std::vector<char> stuck(static_cast<std::size_t>(nf), 0);
  for (int f = 0; f < nf; ++f)
    if ((stuck[f] = stuck_face(maps[f], fixed, X))) {
      result.stuck_faces.push_back(f);
      maps[f].area = 0;
    }
  const auto left = [&](const Eigen::VectorXd& Y) {
    std::vector<int> out;
    for (int f : flipped_triangles(mesh, map_of(mesh, layers, base, Y)).flipped_faces)
      if (!stuck[f]) out.push_back(f);
    return out;
  };
  // Growing regions around the folds: the vertices within k rings of them move (k = rings, ×4 per attempt, then
  // all), everything else stays where it is; most folds are local and a small system untangles them. A region
  // after the first that leaves as many folds as it was given ends the growth: the constraints hold them.
  std::vector<int> folds = left(X);
  bool grow = true;
  for (int rings = std::max(options.rings, 1);
       grow && !folds.empty() && rings <= std::max(options.max_rings, 1) && !progress.cancelled(); rings *= 4) {
    std::vector<char> seed(static_cast<std::size_t>(nv), 0);
    for (int f : folds)
      for (int c = 0; c < 3; ++c) seed[mesh.F()(f, c)] = 1;
    const bool everything = rings * 4 > options.max_rings && options.max_rings >= nf;
    const std::vector<char> in = everything ? seed : grow_vertex_rings(mesh, std::move(seed), rings);
    std::vector<char> region_fixed = fixed;
    for (int p = 0; p < nv && !everything; ++p)
      if (!in[p]) region_fixed[p] = region_fixed[nv + p] = 1;
    ++result.regions;
    const RegionFolds region_folds(mesh, layers, base, stuck, region_fixed, X);
    untangle_region(maps, region_fixed, region_folds, options, progress, X, result);
    const std::size_t given = folds.size();
    folds = left(X);
    grow = !everything && (rings == std::max(options.rings, 1) || folds.size() < given);
  }
  result.unresolved_faces = folds;
  const int after = flipped_triangles(mesh, map_of(mesh, layers, base, X)).non_positive;
  progress.report("param", -1, "untangling: " + std::to_string(after) + " non-positive triangles");
  result.seconds = seconds_since(start);
  const Energy energy(maps, options.area_weight);
  if (after > before) {
    result.unresolved_faces = left(stacked(u0));
    result.min_det = energy.min_det(stacked(u0));
    return u0;
  }
  result.non_positive_after = after;
  result.min_det = energy.min_det(X);
  return unstacked(X);
}

Eigen::VectorXcd polish_map(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                            const FramePairs& Z, const std::vector<char>& fixed, const Eigen::VectorXcd& u0,
                            const std::vector<int>& region, const UntangleOptions& options, ProgressSink& progress,
                            ParamDiagnostics::Untangling& result) {
  const int nv = mesh.num_vertices();
  if (static_cast<int>(fixed.size()) != 2 * nv || u0.size() != nv)
    throw InputError("", 0, "polish_map: the fixed components or u0 do not match the mesh");
  Eigen::VectorXd X = stacked(u0);
  if (region.empty() || flipped_triangles(mesh, map_of(mesh, layers, base, X)).non_positive > 0) return u0;
  std::vector<char> region_fixed(static_cast<std::size_t>(2 * nv), 1);
  for (int p : region) region_fixed[p] = fixed[p], region_fixed[nv + p] = fixed[nv + p];
  untangle_region(
      face_maps(mesh, layers, base, Z), region_fixed, [](const Eigen::VectorXd&) { return 0; }, options, progress, X,
      result);
  return unstacked(X);
}

}  // namespace quadcover
