#include "param/stiffening.h"

#include <algorithm>
#include <cmath>

#include "cover/complex_stiffness.h"
#include "param/seams.h"

namespace quadcover {

Eigen::VectorXd frame_distortion(const Mesh& mesh, const Eigen::MatrixX3cd& uv, const FramePairs& Z) {
  const int nf = mesh.num_faces();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(nf);
  for (int f = 0; f < nf; ++f) {
    const auto [g0, g1] = face_gradient(mesh, uv, f);
    // Rows of G = ∇φ⁰, ∇φ¹ and of T = Z⁰, Z¹ (2-vectors in f's local frame); J = G T⁻¹.
    const double t00 = Z(f, 0).real(), t01 = Z(f, 0).imag(), t10 = Z(f, 1).real(), t11 = Z(f, 1).imag();
    const double det_t = t00 * t11 - t01 * t10;
    if (!(std::abs(det_t) > 1e-300) || !std::isfinite(det_t)) continue;
    const double i00 = t11 / det_t, i01 = -t01 / det_t, i10 = -t10 / det_t, i11 = t00 / det_t;
    const double a = g0.real() * i00 + g0.imag() * i10, b = g0.real() * i01 + g0.imag() * i11;
    const double c = g1.real() * i00 + g1.imag() * i10, e = g1.real() * i01 + g1.imag() * i11;
    // Signed singular values of [a b; c e]: σ₁ = q + r, σ₂ = q − r with q² − r² = det J.
    const double q = std::hypot(0.5 * (a + e), 0.5 * (c - b)), r = std::hypot(0.5 * (a - e), 0.5 * (c + b));
    d[f] = std::abs(q + r - 1) + std::abs(q - r - 1);
  }
  return d;
}

Eigen::VectorXcd stiffen_correction(const Mesh& mesh, const Eigen::VectorXi& matching,
                                    const HarmonicCorrection& correction, const Eigen::MatrixX3cd& base,
                                    const FramePairs& Z, const FramePairs& target,
                                    const Eigen::VectorXcd& u0, const WeightedCorrectionSolve& solve,
                                    const StiffeningOptions& options, ProgressSink& progress,
                                    ParamDiagnostics::Stiffening& result) {
  const int nf = mesh.num_faces();
  auto map_of = [&](const Eigen::VectorXcd& u) { return Eigen::MatrixX3cd(base - correction.corner_values(u)); };
  Eigen::MatrixX3cd uv = map_of(u0);
  int best_flips = flipped_triangles(mesh, uv).non_positive;
  result = {};
  result.flipped_before = result.flipped_after = best_flips;
  Eigen::VectorXcd best = u0;
  Eigen::VectorXd w = Eigen::VectorXd::Ones(nf);
  int since_better = 0;
  for (int it = 0; it < options.max_iterations && best_flips > 0 && since_better < options.patience; ++it) {
    if (progress.skip_improvements()) break;
    const Eigen::VectorXd d = frame_distortion(mesh, uv, Z);
    for (int f = 0; f < nf; ++f) w[f] += options.strength * std::min(d[f], options.max_distortion);
    FramePairs weighted = target;
    for (int f = 0; f < nf; ++f) weighted.row(f) *= w[f];
    const Eigen::VectorXcd u = solve(complex_conforming_stiffness(mesh, matching, w), correction.rhs(weighted), true);
    uv = map_of(u);
    const int flips = flipped_triangles(mesh, uv).non_positive;
    ++result.iterations;
    progress.report("param", -1, "stiffening: " + std::to_string(flips) + " flipped triangles");
    if (flips < best_flips) {
      best_flips = flips;
      result.kept_iteration = result.iterations;
      best = u;
      since_better = 0;
    } else {
      ++since_better;
    }
  }
  result.flipped_after = best_flips;
  return best;
}

}  // namespace quadcover
