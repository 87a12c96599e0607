#pragma once
// As-rigid-as-possible relaxation of the final map (beyond the thesis; local/global ARAP, Liu et al. 2008, on the
// integer-grid map). The thesis map φ = φ̂ + σ − u follows the scaled frame Z as closely as the rounded periods
// allow (E_D + E_H, 6.1.1); the curl part E_D shows as scale and shear distortion. With the seams, periods, branch
// points and curve constraints fixed, the covering function u is re-solved so that ∇φ_t follows the rotation
// R_t nearest to the current Jacobian instead of the frame:
//   min_u Σ_t A_t [(1 − α) |∇φ_t − s R_t|² + α |∇φ_t − Z_t|²],   φ = base − u,
// alternating R_t (local step, closed form in 2D) and u (global step: the harmonic correction's system, same
// matrix, new right-hand side). Each step lowers the energy; α keeps the quads oriented by the field.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "common/progress.h"
#include "param/disk_functions.h"
#include "param/harmonic_correction.h"
#include "param/parameterization.h"

namespace quadcover {

struct RelaxationOptions {
  int iterations = 20;        ///< local/global rounds at most; 0 turns relaxation off
  double field_weight = 0.1;  ///< α: share of the frame Z in the target (1: no relaxation)
  double tolerance = 1e-4;    ///< stop when the energy falls by less than this fraction in one round
  /// When a round leaves a triangle flipped that has no extra weight yet, every flipped triangle gets this much
  /// more weight A_t w_t in the following rounds (the matrix is refactored then; other rounds only re-solve). The
  /// nearest rotation of a flipped triangle is its way back to a positive orientation.
  double flip_weight = 10.0;
  /// Refactorizations at most: refactorization_budget / #F, between 2 and `iterations`. More of them keep
  /// unflipping triangles, but each costs a factorization (BENCHMARKS.md, "Option defaults"). The default allows
  /// 20 up to 50k faces and 2 from 500k faces on.
  double refactorization_budget = 1e6;
};

/// Per face, the target gradient pair (∇φ⁰, ∇φ¹) = s R_t of the rotation nearest to the map's Jacobian on f
/// (R_t = argmin over proper rotations of ‖J_t − R‖_F, J_t rows ∇φ⁰, ∇φ¹ in f's frame), from the map's gradients
/// (corner_gradient). \pre s > 0
FramePairs nearest_rotations(const FramePairs& gradient, double s);
/// The same at scale s·ρ_t on face t (ρ: #F, or empty for 1). \pre as above; ρ empty or #F.
FramePairs nearest_rotations(const FramePairs& gradient, double s, const Eigen::VectorXd& rho);

/// ½ Σ_t A_t |∇φ_t − s R_t|² / (s² Σ_t A_t): the mean ARAP distortion of the map at scale s (R_t as above).
/// \pre uv is #F by 3; s > 0.
double rigidity_energy(const Mesh& mesh, const Eigen::MatrixX3cd& uv, double s);
/// The same with face t at scale s·ρ_t (components of different densities, param/density.h):
/// ½ Σ_t A_t |∇φ_t − s ρ_t R_t|² / (s² Σ_t A_t ρ_t²). \pre as above; ρ empty (1) or #F.
double rigidity_energy(const Mesh& mesh, const Eigen::MatrixX3cd& uv, double s, const Eigen::VectorXd& rho);

struct RelaxedCorrection {
  Eigen::VectorXcd u;
  /// ∇(base) − G: the target of ∇u for the final targets G = (1 − α) s R + α Z (what later weighted solves follow).
  FramePairs target;
  /// G itself: the per-face gradient the relaxed map follows.
  FramePairs gradient_target;
};

/// The relaxation loop from u0 (φ = base − corner_values(u)); Z the scaled gauged frame, s its RMS length
/// (grid units per model unit), ρ per face the density factor of its component (param/density.h face_density; Z is
/// s·ρ_t long on face t). Fills `result` (iterations and the energies of rigidity_energy before and after)
/// except its price.
/// \pre as in param/parameterize.cpp: matching #E, base #F by 3, Z #F by 2, u0 #V, s > 0. \throw NumericalError if a
/// solve fails.
RelaxedCorrection relax_correction(const Mesh& mesh, const Eigen::VectorXi& matching,
                                   const HarmonicCorrection& correction, const Eigen::MatrixX3cd& base,
                                   const FramePairs& Z, double s, const Eigen::VectorXd& rho,
                                   const Eigen::VectorXcd& u0, const CorrectionResolve& resolve,
                                   const WeightedCorrectionSolve& weighted_solve, const RelaxationOptions& options,
                                   ProgressSink& progress, ParamDiagnostics::Relaxation& result);

}  // namespace quadcover
