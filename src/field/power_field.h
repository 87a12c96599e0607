#pragma once
// Global smooth fill of a cross field in its 4-RoSy "power" representation u_t = (X_t/|X_t|)^4 (beyond the
// thesis: replaces the breadth-first propagation of 5.1.2, whose seams between propagated regions leave many
// spurious branch points that smoothing with a fixed matching (5.3) cannot remove).
//
// A cross {±X, ±iX} is one complex number u = X^4, and the transport of crosses across an edge is u ↦ ρ_e^4 u,
// free of any matching. Minimizing a quadratic energy in u is therefore one sparse Hermitian solve, and the
// matching and the branch points come out of the result instead of being fixed beforehand.
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

/// The quadratic energy minimized by smooth_power_field (all terms dimensionless and independent of the scale
/// and resolution of the mesh):
///   E(u) = Σ_e ω_e |u_t - ρ_e^4 u_s|²  +  μ Σ_t a_t (A_t / A_M) |u_t - c_t|²,
/// ω_e = ‖e‖²/A_e the weights of E_S (thesis 5.2, ≈ 2∫|∇u|² on fine meshes), a_t >= 0 the per-face alignment
/// weights, c_t = d_t^4 the powered target directions, A_M the area of the face's connected component.
/// μ is the alignment strength: features of the target smaller than about 1/√μ of the component's size are
/// smoothed away.
struct PowerFieldProblem {
  Eigen::VectorXcd target;   ///< #F target directions d_t (any nonzero length; only the direction is used)
  Eigen::VectorXd weight;    ///< #F alignment weights a_t >= 0 (0: the face only follows its neighbours)
  std::vector<char> fixed;   ///< #F (or empty): faces whose cross is d_t exactly (hard constraint)
  double alignment = 100.0;  ///< μ
  /// Ginzburg–Landau weight σ >= 0: after the linear solve, `iterations` majorize-minimize steps decrease
  ///   E(u) + σ Σ_t (A_t/A_M) (|u_t| - 1)²,
  /// each minimizing E(u) + σ Σ_t (A_t/A_M)|u_t - u⁰_t/|u⁰_t||² around the previous iterate u⁰ (one factorization
  /// of the matrix for all steps, then two triangular solves per step). The unit-length penalty makes every
  /// singularity cost energy ~ log(core size), so nearby ± pairs annihilate; σ ~ 1/ε², ε the core radius as a
  /// fraction of √A_M. 0 keeps the linear solution.
  double unit_weight = 0.0;
  int iterations = 0;  ///< majorize-minimize steps (fewer once no u_t turns by more than 1e-6 rad in a step)
};

struct PowerFieldResult {
  Eigen::VectorXcd u;  ///< #F the minimizer of E (not normalized; |u_t| is small near singularities)
  Eigen::VectorXcd X;  ///< #F unit first frame vectors, X_t^4 = u_t/|u_t| (X_t = d_t exactly at fixed faces)
  /// Faces held at u_t = c_t: `fixed` plus, in every connected component with neither a fixed face nor a positive
  /// weight, its face of lowest index (E would be invariant under a common rotation there).
  std::vector<char> held;
  int iterations = 0;  ///< majorize-minimize steps taken
};

/// Minimizer of E (see PowerFieldProblem) with u_t = c_t on the fixed faces, one sparse Hermitian positive
/// definite solve (SparseCholesky<Complex>).
/// \throw std::invalid_argument on wrong sizes, negative weights or μ < 0; NumericalError if the factorization fails.
PowerFieldResult smooth_power_field(const Mesh& mesh, const PowerFieldProblem& problem);

/// E(u) of PowerFieldProblem evaluated directly (for tests and reports); with `ginzburg_landau` the term
/// σ Σ_t (A_t/A_M)(|u_t| - 1)² is added. \pre u and the problem's arrays have #F entries.
double power_field_energy(const Mesh& mesh, const PowerFieldProblem& problem, const Eigen::VectorXcd& u,
                          bool ginzburg_landau = false);

}  // namespace quadcover
