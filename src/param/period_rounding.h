#pragma once
// Rounding of the periods b to integers c with the smallest continuity distortion (thesis 6.3):
//   E_H = ½ dᵀ P d,  d = c - b,  P_ij = ⟨H_i, H_j⟩ the period matrix of the harmonic basis fields.
// Minimizing E_H over c ∈ Zⁿ is a closest-vector problem (6.3: B = Cholesky factor of P, target B b).
#include <Eigen/Core>
#include <functional>
#include <string>
#include <string_view>

namespace quadcover {

enum class RoundingStrategy {
  Direct,   ///< c = [b], entrywise nearest integer (2.4.2, 4.2.1)
  Greedy,   ///< MIQ-style: fix one variable at a time, the one whose rounding raises the relaxed energy least
  Search1,  ///< from [b], change one entry by ±1 while E_H decreases (δ formula of 6.3.1)
  Search2,  ///< ... up to two entries at a time
  Search3,  ///< ... up to three entries at a time (the thesis's method, r = 3); also from the greedy start
  Exact,    ///< exact closest vector (LLL + enumeration) when n <= exact_max_dimension, else Search3
};

/// Parses "direct|greedy|search1|search2|search3|exact". \throw InputError for anything else.
RoundingStrategy parse_rounding_strategy(std::string_view name);
std::string to_string(RoundingStrategy strategy);  ///< \pre none

struct RoundingOptions {
  RoundingStrategy strategy = RoundingStrategy::Search3;
  /// Exact CVP only up to this dimension (enumeration is exponential); larger instances fall back to Search3.
  int exact_max_dimension = 48;
  /// Search3 also runs from the Greedy solution and keeps the better result (beyond the thesis).
  bool search3_from_greedy = true;
  /// Exact: enumeration node budget; when exhausted the best vector found is returned, not proven optimal.
  long long exact_max_nodes = 200'000'000;
  /// Search: a move must lower dᵀPd by more than this times tr(P) (prevents cycling on round-off).
  double relative_tolerance = 1e-13;
  /// Asked between search passes (Ctrl-C, time limit): when it returns true the search stops with the best vector
  /// so far (each accepted move lowers E_H, so that is never worse than the start).
  std::function<bool()> stop;
  /// Search strategies stop (best so far, stopped_early) after this many candidate evaluations: the r = 3 pass is
  /// O(n³), so huge instances (thousands of periods on 10⁶-face meshes) stay within seconds.
  long long max_candidates = 2'000'000'000;
};

struct RoundingResult {
  Eigen::VectorXi c;            ///< n rounded periods
  double energy = 0;            ///< E_H = ½ (c-b)ᵀ P (c-b)
  long long candidates = 0;     ///< candidate vectors whose energy change was evaluated (search strategies)
  int moves = 0;                ///< accepted search moves / fixed variables
  bool proven_optimal = false;  ///< true if the exact CVP solver ran and its result was not beaten
  bool stopped_early = false;   ///< options.stop asked the search to stop
  RoundingStrategy used = RoundingStrategy::Direct;  ///< the strategy that actually ran (Exact may fall back)
};

/// E_H = ½ (c - b)ᵀ P (c - b). \pre P is n by n; b, c have n entries.
double rounding_energy(const Eigen::MatrixXd& P, const Eigen::VectorXd& b, const Eigen::VectorXi& c);

/// Rounds b to integers minimizing E_H with the chosen strategy.
/// P  n by n symmetric positive definite; b  n periods.
/// \throw InputError if the sizes disagree; NumericalError if P is not positive definite (Greedy, Exact).
RoundingResult round_periods(const Eigen::MatrixXd& P, const Eigen::VectorXd& b, const RoundingOptions& options = {});

/// Exact closest vector argmin_c (c-b)ᵀP(c-b): LLL reduction (fplll) of the lattice basis B, P = BᵀB, then
/// Schnorr–Euchner enumeration within the squared radius bound2 (pass 2·E_H of a heuristic solution).
/// Exponential in n; stops after max_nodes enumeration nodes. \return empty if nothing lies within the bound;
/// *proven (if given) tells whether the enumeration completed, i.e. the result is optimal.
/// \pre P is n by n symmetric positive definite; b has n entries; bound2 >= 0.
Eigen::VectorXi closest_vector_exact(const Eigen::MatrixXd& P, const Eigen::VectorXd& b, double bound2,
                                     long long max_nodes = 200'000'000, bool* proven = nullptr);

}  // namespace quadcover
