#include "param/period_rounding.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

#include "common/errors.h"

namespace quadcover {

RoundingStrategy parse_rounding_strategy(std::string_view name) {
  if (name == "direct") return RoundingStrategy::Direct;
  if (name == "greedy") return RoundingStrategy::Greedy;
  if (name == "search1") return RoundingStrategy::Search1;
  if (name == "search2") return RoundingStrategy::Search2;
  if (name == "search3") return RoundingStrategy::Search3;
  if (name == "exact") return RoundingStrategy::Exact;
  throw InputError("", 0, "unknown rounding strategy '" + std::string(name) +
                              "' (expected direct, greedy, search1, search2, search3 or exact)");
}

std::string to_string(RoundingStrategy strategy) {
  switch (strategy) {
    case RoundingStrategy::Direct: return "direct";
    case RoundingStrategy::Greedy: return "greedy";
    case RoundingStrategy::Search1: return "search1";
    case RoundingStrategy::Search2: return "search2";
    case RoundingStrategy::Search3: return "search3";
    case RoundingStrategy::Exact: return "exact";
  }
  return "?";
}

double rounding_energy(const Eigen::MatrixXd& P, const Eigen::VectorXd& b, const Eigen::VectorXi& c) {
  const Eigen::VectorXd d = c.cast<double>() - b;
  return 0.5 * d.dot(P * d);
}

namespace {

Eigen::VectorXi round_direct(const Eigen::VectorXd& b) {
  Eigen::VectorXi c(b.size());
  for (Eigen::Index i = 0; i < b.size(); ++i) c[i] = static_cast<int>(std::lround(b[i]));
  return c;
}

// Local search changing up to r entries of c by ±1 (6.3.1). g = P(c - b) is kept up to date, so the change of
// dᵀPd for a move σ on the index set S is δ = Σ_S (P_ii + 2σ_i g_i) + 2 Σ_{i<j ∈ S} σ_iσ_j P_ij.
class Search {
 public:
  Search(const Eigen::MatrixXd& P, const Eigen::VectorXd& b, Eigen::VectorXi c, double tol,
         const std::function<bool()>& stop, long long max_candidates)
      : P_(P), c_(std::move(c)), n_(static_cast<int>(P.rows())), tol_(tol), stop_(stop), budget_(max_candidates) {
    g_ = P_ * (c_.cast<double>() - b);
  }
  void run(int r) {
    for (;;) {
      if (out_of_budget() || (stop_ && stop_())) {
        stopped = true;
        break;
      }
      if (pass1()) continue;
      if (r >= 2 && pass2()) continue;
      if (r >= 3 && pass3()) continue;
      stopped = out_of_budget();  // a pass cut short by the budget is not a proven local minimum
      break;
    }
  }
  const Eigen::VectorXi& c() const { return c_; }
  long long candidates = 0;
  int moves = 0;
  bool stopped = false;

 private:
  bool out_of_budget() const { return budget_ > 0 && candidates >= budget_; }
  void apply(int i, int s) {
    c_[i] += s;
    g_ += s * P_.col(i);
  }
  bool pass1() {
    bool improved = false;
    for (int i = 0; i < n_; ++i)
      for (int s : {1, -1}) {
        ++candidates;
        if (P_(i, i) + 2 * s * g_[i] < -tol_) {
          apply(i, s);
          ++moves;
          improved = true;
        }
      }
    return improved;
  }
  bool pass2() {
    for (int i = 0; i < n_; ++i)
      for (int j = i + 1; j < n_; ++j)
        for (int si : {1, -1})
          for (int sj : {1, -1}) {
            ++candidates;
            const double delta = P_(i, i) + P_(j, j) + 2 * (si * g_[i] + sj * g_[j] + si * sj * P_(i, j));
            if (delta < -tol_) {
              apply(i, si), apply(j, sj);
              ++moves;
              return true;
            }
          }
    return false;
  }
  // For fixed (i, σ_i, j, σ_j) the best third entry k is the one minimizing P_kk - 2|h_k| with
  // h_k = g_k + σ_i P_ik + σ_j P_jk (σ_k = -sign h_k): both signs of every k are covered by one evaluation.
  bool pass3() {
    diag_.resize(n_);
    for (int k = 0; k < n_; ++k) diag_[k] = P_(k, k);
    for (int i = 0; i < n_ && !out_of_budget(); ++i) {
      const double* Pi = P_.col(i).data();
      for (int j = i + 1; j < n_; ++j) {
        const double* Pj = P_.col(j).data();
        for (int si : {1, -1})
          for (int sj : {1, -1}) {
            const double base = Pi[i] + Pj[j] + 2 * (si * g_[i] + sj * g_[j] + si * sj * Pi[j]);
            const double* g = g_.data();
            int best = -1;
            double best_delta = -tol_;
            for (int k = j + 1; k < n_; ++k) {
              const double h = g[k] + si * Pi[k] + sj * Pj[k];
              const double delta = base + diag_[k] - 2 * std::abs(h);
              if (delta < best_delta) best_delta = delta, best = k;
            }
            candidates += 2LL * (n_ - j - 1);
            if (best >= 0) {
              const double h = g_[best] + si * Pi[best] + sj * Pj[best];
              apply(i, si), apply(j, sj), apply(best, h > 0 ? -1 : 1);
              ++moves;
              return true;
            }
          }
      }
    }
    return false;
  }

  const Eigen::MatrixXd& P_;
  Eigen::VectorXi c_;
  Eigen::VectorXd g_;
  std::vector<double> diag_;
  int n_;
  double tol_;
  const std::function<bool()>& stop_;
  long long budget_;
};

// MIQ-style greedy rounding [BZK09] as described in 6.3.3: starting from the relaxed optimum y = b, repeatedly fix
// the free variable whose rounding raises the relaxed energy least; the raise for fixing y_i to z is
// (z - y_i)² / (Q⁻¹)_ii with Q the free block of P, and Q⁻¹ loses row/column i by a rank-1 Schur update.
Eigen::VectorXi round_greedy(const Eigen::MatrixXd& P, const Eigen::VectorXd& b, int& moves) {
  const int n = static_cast<int>(P.rows());
  Eigen::LLT<Eigen::MatrixXd> llt(P);
  if (llt.info() != Eigen::Success) throw NumericalError("rounding", "period matrix is not positive definite");
  Eigen::MatrixXd Qinv = llt.solve(Eigen::MatrixXd::Identity(n, n));
  Eigen::VectorXd y = b;
  Eigen::VectorXi c = Eigen::VectorXi::Zero(n);
  std::vector<char> fixed(n, 0);
  for (int step = 0; step < n; ++step) {
    int best = -1;
    double best_raise = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      if (fixed[i]) continue;
      const double r = std::round(y[i]) - y[i];
      const double raise = r * r / Qinv(i, i);
      if (raise < best_raise) best_raise = raise, best = i;
    }
    const double z = std::round(y[best]);
    const double t = (z - y[best]) / Qinv(best, best);
    const Eigen::VectorXd col = Qinv.col(best);
    y += t * col;
    Qinv.noalias() -= (col / col[best]) * col.transpose();
    fixed[best] = 1;
    c[best] = static_cast<int>(z);
    for (int i = 0; i < n; ++i)
      if (fixed[i]) y[i] = c[i];  // exact values of the fixed variables (the update keeps them up to round-off)
    ++moves;
  }
  return c;
}

}  // namespace

RoundingResult round_periods(const Eigen::MatrixXd& P, const Eigen::VectorXd& b, const RoundingOptions& options) {
  if (P.rows() != P.cols() || P.rows() != b.size())
    throw InputError("", 0, "round_periods: period matrix is " + std::to_string(P.rows()) + "x" +
                                std::to_string(P.cols()) + " but there are " + std::to_string(b.size()) + " periods");
  RoundingResult out;
  out.used = options.strategy;
  const double tol = options.relative_tolerance * std::max(P.trace(), std::numeric_limits<double>::min());
  auto search = [&](int r, Eigen::VectorXi start) {
    Search s(P, b, std::move(start), tol, options.stop, options.max_candidates);
    s.run(r);
    out.candidates += s.candidates;
    out.moves += s.moves;
    out.stopped_early = out.stopped_early || s.stopped;
    return s.c();
  };
  switch (options.strategy) {
    case RoundingStrategy::Direct: out.c = round_direct(b); break;
    case RoundingStrategy::Greedy: out.c = round_greedy(P, b, out.moves); break;
    case RoundingStrategy::Search1: out.c = search(1, round_direct(b)); break;
    case RoundingStrategy::Search2: out.c = search(2, round_direct(b)); break;
    case RoundingStrategy::Search3: {
      // Beyond the thesis: the r = 3 search is started from direct rounding (6.3.1) and from the greedy solution
      // (when P is definite), and the better local minimum is kept.
      out.c = search(3, round_direct(b));
      if (options.search3_from_greedy && !out.stopped_early && Eigen::LLT<Eigen::MatrixXd>(P).info() == Eigen::Success) {
        int greedy_moves = 0;
        const Eigen::VectorXi other = search(3, round_greedy(P, b, greedy_moves));
        if (rounding_energy(P, b, other) < rounding_energy(P, b, out.c)) out.c = other;
      }
      break;
    }
    case RoundingStrategy::Exact: {
      // The heuristic result guards against the (tiny) integer-scaling error of the exact solver.
      RoundingOptions h = options;
      h.strategy = RoundingStrategy::Search3;
      const RoundingResult hr = round_periods(P, b, h);
      out.candidates += hr.candidates;
      out.stopped_early = hr.stopped_early;
      const Eigen::VectorXi heuristic = hr.c;
      if (P.rows() > options.exact_max_dimension || hr.stopped_early) {
        out.c = heuristic;
        out.used = RoundingStrategy::Search3;
        break;
      }
      bool proven = false;
      const double e_heur = rounding_energy(P, b, heuristic);
      Eigen::VectorXi exact = closest_vector_exact(P, b, 2 * e_heur, options.exact_max_nodes, &proven);
      const double e_exact = exact.size() ? rounding_energy(P, b, exact) : e_heur;
      if (!exact.size()) exact = heuristic;  // nothing strictly better inside the radius: the heuristic is optimal
      out.proven_optimal = proven;
      out.c = e_exact <= e_heur ? exact : heuristic;
      break;
    }
  }
  out.energy = rounding_energy(P, b, out.c);
  return out;
}

}  // namespace quadcover
