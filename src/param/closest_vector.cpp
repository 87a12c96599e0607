// Exact rounding (6.3: "equivalent to the closest vector problem") with fplll: LLL-reduce an integer version of
// the lattice basis B (Bᵀ B = P), then our own Schnorr–Euchner enumeration of the closest lattice vector
// (fplll 5.4's closest_vector() returned non-optimal vectors on our test instances, so it is not used).
#include <fplll.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>

#include "common/errors.h"
#include "param/period_rounding.h"

namespace quadcover {

namespace {

// Schnorr–Euchner enumeration of argmin_s Σ_i (R_ii(s_i - c_i(s)))², c_i the projected centre, for upper
// triangular R, pruned by the squared radius `bound` (zig-zag order around each centre, deepest index first).
struct Enumeration {
  const Eigen::MatrixXd& R;
  const Eigen::VectorXd& target;
  double bound;
  long long nodes = 0, max_nodes;
  Eigen::VectorXd s, best;
  bool found = false, exhausted = false;

  void run() {
    s = Eigen::VectorXd::Zero(target.size());
    level(static_cast<int>(target.size()) - 1, 0.0);
  }
  void level(int i, double dist) {
    if (exhausted) return;
    double shift = 0;  // Σ_{j>i} R_ij (s_j - t_j)
    for (int j = i + 1; j < s.size(); ++j) shift += R(i, j) * (s[j] - target[j]);
    const double centre = target[i] - shift / R(i, i);
    double v = std::round(centre);
    // Zig-zag: centre's nearest integer, then alternately the next ones on either side.
    const double dir0 = centre >= v ? 1.0 : -1.0;
    for (int step = 0;; ++step) {
      const double y = R(i, i) * (v - centre);
      const double d = dist + y * y;
      if (d > bound) return;  // later candidates at this level are farther still
      if (++nodes > max_nodes) {
        exhausted = true;
        return;
      }
      s[i] = v;
      if (i == 0) {
        bound = d, best = s, found = true;
      } else {
        level(i - 1, d);
        if (exhausted) return;
      }
      // next candidate: round(centre) + dir0·(1, -1, 2, -2, ...) pattern
      const int k = step + 1;
      v = std::round(centre) + (k % 2 ? dir0 : -dir0) * ((k + 1) / 2);
    }
  }
};

}  // namespace

Eigen::VectorXi closest_vector_exact(const Eigen::MatrixXd& P, const Eigen::VectorXd& b, double bound2,
                                     long long max_nodes, bool* proven) {
  const int n = static_cast<int>(P.rows());
  if (proven) *proven = false;
  if (n == 0) return {};
  Eigen::LLT<Eigen::MatrixXd> llt(P);
  if (llt.info() != Eigen::Success) throw NumericalError("rounding", "period matrix is not positive definite");
  const Eigen::MatrixXd R = llt.matrixU();  // P = RᵀR: (c-b)ᵀP(c-b) = ‖Rc - Rb‖²
  // LLL with fplll on an integer copy of the basis (rows = columns of R, ~40 significant bits); only the
  // unimodular transform U is used, so the rounding of the copy cannot make the result inexact.
  const double scale = std::ldexp(1.0, 40 - std::ilogb(R.cwiseAbs().maxCoeff()));
  fplll::ZZ_mat<mpz_t> basis(n, n), transform;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) basis[i][j] = static_cast<long>(std::llround(scale * R(j, i)));
  transform.gen_identity(n);
  if (fplll::lll_reduction(basis, transform) != fplll::RED_SUCCESS)
    throw NumericalError("rounding", "LLL reduction of the period lattice failed");
  Eigen::MatrixXd U(n, n);  // reduced rows = U · original rows, c = Uᵀ s
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) U(i, j) = static_cast<double>(transform[i][j].get_si());
  // In the reduced coordinates s: (c-b)ᵀP(c-b) = (s - s*)ᵀ G (s - s*), G = U P Uᵀ, s* = U⁻ᵀ b.
  const Eigen::MatrixXd G = U * P * U.transpose();
  const Eigen::VectorXd s_star = U.transpose().fullPivLu().solve(b);
  Eigen::LLT<Eigen::MatrixXd> gllt(G);
  if (gllt.info() != Eigen::Success) throw NumericalError("rounding", "reduced Gram matrix is not positive definite");
  const Eigen::MatrixXd Rg = gllt.matrixU();
  Enumeration e{Rg, s_star, bound2 * (1 + 1e-12) + 1e-300, 0, max_nodes, {}, {}};
  e.run();
  if (!e.found) return {};
  if (proven) *proven = !e.exhausted;
  const Eigen::VectorXd c = U.transpose() * e.best;
  Eigen::VectorXi out(n);
  for (int i = 0; i < n; ++i) out[i] = static_cast<int>(std::lround(c[i]));
  return out;
}

}  // namespace quadcover
