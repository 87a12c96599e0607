#pragma once
// Local stiffening of the final solve (beyond the thesis; the idea of MIQ's local stiffening, Bommes et al. 2009).
// With the rounded periods and the branch points fixed, φ = φ̂ + σ − u and ∇φ − Z = T − ∇u with T = Σ̃_d − X̃_C, so
// the harmonic correction u minimizes Σ_t w_t A_t |T_t − ∇u_t|² for w ≡ 1 (giving E_D + E_H, 6.1.1). Raising w_t on
// distorted and flipped triangles pulls them towards the field (a frame is never flipped) at the price of
// E_K = ½‖X̃ − ∇φ̃‖² − E_D − E_H ≥ 0. u stays a covering function (0 at branch points): seams stay exact, branch
// points stay on their integer points, curve constraints stay enforced (the caller's solver keeps them).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>

#include "common/progress.h"
#include "param/disk_functions.h"
#include "param/harmonic_correction.h"
#include "param/parameterization.h"

namespace quadcover {

struct StiffeningOptions {
  /// Re-solves at most; 0 (default) turns stiffening off: the untangler (param/untangle.h) makes the final map
  /// injective where the subspace allows, and with it stiffening changed no count on the shipped meshes.
  int max_iterations = 0;
  double strength = 1.0;        ///< c in w_t ← w_t + c · min(d_t, max_distortion)
  double max_distortion = 5.0;  ///< cap of d_t per iteration
  int patience = 3;             ///< stop after this many re-solves without fewer flipped triangles
};

/// Per face: d = |σ₁ − 1| + |σ₂ − 1| for the singular values of J = (∇φ) Z⁻¹ (the map relative to the frame it
/// should follow), σ₂ carrying the sign of det J, so a flipped triangle has d > 1. 0 where Z is degenerate.
/// \pre uv is #F by 3; Z is #F by 2.
Eigen::VectorXd frame_distortion(const Mesh& mesh, const Eigen::MatrixX3cd& uv, const FramePairs& Z);

/// The stiffening loop from the unweighted solution u0: re-solves with w += c·d while triangles are flipped and
/// returns the u with the fewest flipped triangles (u0 unless a re-solve strictly improves on it; re-solve k is the
/// k-th call of `solve`, reported as result.kept_iteration). `base` holds the
/// corner values of φ̂ + σ (φ = base − u), `target` = T = Σ̃_d − X̃_C, Z the scaled gauged field. Fills `result`
/// except its price E_K (the caller knows E_H).
/// \pre matching #E, base #F by 3, Z and target #F by 2, u0 #V. \throw NumericalError if a solve fails.
Eigen::VectorXcd stiffen_correction(const Mesh& mesh, const Eigen::VectorXi& matching,
                                    const HarmonicCorrection& correction, const Eigen::MatrixX3cd& base,
                                    const FramePairs& Z, const FramePairs& target,
                                    const Eigen::VectorXcd& u0, const WeightedCorrectionSolve& solve,
                                    const StiffeningOptions& options, ProgressSink& progress,
                                    ParamDiagnostics::Stiffening& result);

}  // namespace quadcover
