#include "param/relaxation.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "cover/complex_stiffness.h"
#include "param/seams.h"

namespace quadcover {

namespace {

// Angle θ of the proper rotation nearest to J = [a b; c d] (rows ∇φ⁰ = a + ib, ∇φ¹ = c + id):
// tr(RᵀJ) = cos θ (a + d) + sin θ (c − b) is largest at θ = atan2(c − b, a + d). Its rows are
// (cos θ, −sin θ) = e^{−iθ} and (sin θ, cos θ) = i e^{−iθ}.
Complex nearest_rotation_row0(Complex g0, Complex g1) {
  const double x = g0.real() + g1.imag(), y = g1.real() - g0.imag();
  const double r = std::hypot(x, y);
  if (!(r > 0)) return 1;  // J ≡ 0 (a collapsed triangle): any rotation is nearest
  return {x / r, -y / r};
}

}  // namespace

FramePairs nearest_rotations(const FramePairs& gradient, double s, const Eigen::VectorXd& rho) {
  const Eigen::Index nf = gradient.rows();
  FramePairs R(nf, 2);
  for (Eigen::Index f = 0; f < nf; ++f) {
    const Complex r0 = nearest_rotation_row0(gradient(f, 0), gradient(f, 1));
    const double sf = rho.size() == 0 ? s : rho[f] * s;
    R(f, 0) = sf * r0;
    R(f, 1) = sf * Complex(0, 1) * r0;
  }
  return R;
}

FramePairs nearest_rotations(const FramePairs& gradient, double s) { return nearest_rotations(gradient, s, {}); }

double rigidity_energy(const Mesh& mesh, const Eigen::MatrixX3cd& uv, double s, const Eigen::VectorXd& rho) {
  const FramePairs G = corner_gradient(mesh, uv);
  const bool uniform = rho.size() == 0 || (rho.array() == 1.0).all();
  const double area = uniform ? mesh.total_area() : mesh.face_areas().dot(rho.cwiseAbs2());  // Σ_t A_t ρ_t²
  return 0.5 * frame_norm2(mesh, G - nearest_rotations(G, s, rho)) / (s * s * area);
}

double rigidity_energy(const Mesh& mesh, const Eigen::MatrixX3cd& uv, double s) {
  return rigidity_energy(mesh, uv, s, {});
}

RelaxedCorrection relax_correction(const Mesh& mesh, const Eigen::VectorXi& matching,
                                   const HarmonicCorrection& correction, const Eigen::MatrixX3cd& base,
                                   const FramePairs& Z, double s, const Eigen::VectorXd& rho,
                                   const Eigen::VectorXcd& u0, const CorrectionResolve& resolve,
                                   const WeightedCorrectionSolve& weighted_solve, const RelaxationOptions& options,
                                   ProgressSink& progress, ParamDiagnostics::Relaxation& result) {
  const int nf = mesh.num_faces();
  const double alpha = options.field_weight;
  const FramePairs base_gradient = corner_gradient(mesh, base);
  RelaxedCorrection out{u0, {}, Z};
  auto map_of = [&](const Eigen::VectorXcd& u) { return Eigen::MatrixX3cd(base - correction.corner_values(u)); };
  // G = (1 − α) s R(φ) + α Z and the blended energy at (φ, R(φ)), the quantity each local and global step lowers
  // (for fixed weights).
  auto targets_of = [&](const Eigen::MatrixX3cd& uv, FramePairs& G) {
    const FramePairs grad = corner_gradient(mesh, uv), R = nearest_rotations(grad, s, rho);
    G = (1 - alpha) * R + alpha * Z;
    return 0.5 * ((1 - alpha) * frame_norm2(mesh, grad - R) + alpha * frame_norm2(mesh, grad - Z));
  };
  Eigen::MatrixX3cd uv = map_of(u0);
  result = {};
  result.rigidity_before = result.rigidity_after = rigidity_energy(mesh, uv, s, rho);
  FramePairs G;
  double energy = targets_of(uv, G);
  Eigen::VectorXd w = Eigen::VectorXd::Ones(nf);
  bool weighted = false, weights_changed = false;
  int refactorizations = 0;
  const int max_refactorizations = std::clamp(static_cast<int>(options.refactorization_budget / std::max(1, nf)), 2,
                                              std::max(2, options.iterations));
  Eigen::SparseMatrix<Complex> Lw;
  for (int it = 0; it < options.iterations && alpha < 1; ++it) {
    if (progress.skip_improvements()) {
      result.stopped_early = true;
      break;
    }
    FramePairs target = base_gradient - G;  // ∇u ≈ ∇base − G  ⇔  ∇φ ≈ G
    Eigen::VectorXcd u;
    if (weighted) {
      for (int f = 0; f < nf; ++f) target.row(f) *= w[f];
      if (weights_changed) Lw = complex_conforming_stiffness(mesh, matching, w);
      u = weighted_solve(Lw, correction.rhs(target), weights_changed);
    } else {
      u = resolve(correction.rhs(target));
    }
    uv = map_of(u);
    ++result.iterations;
    out.u = u;
    out.gradient_target = G;
    const double next = targets_of(uv, G);
    const FlipReport flips = flipped_triangles(mesh, uv);
    // Refactor only when a triangle flips that has no extra weight yet (then every flipped one gets more).
    weights_changed = false;
    for (int f : flips.flipped_faces) weights_changed = weights_changed || w[f] == 1;
    weights_changed = weights_changed && options.flip_weight > 0 && refactorizations < max_refactorizations;
    if (weights_changed) {
      ++refactorizations;
      for (int f : flips.flipped_faces) w[f] += options.flip_weight;
    }
    weighted = weighted || weights_changed;
    progress.report("param", -1,
                    "relaxation " + std::to_string(it + 1) + ": energy " + std::to_string(next) + ", " +
                        std::to_string(flips.flipped) + " flipped");
    // Converged: the energy of these weights settled (a round that changed the weights does not count), and no
    // triangle is left that more weight could unflip.
    const bool settled = !weights_changed && std::abs(energy - next) < options.tolerance * energy;
    energy = next;
    if (settled && (flips.flipped_faces.empty() || refactorizations >= max_refactorizations)) break;
  }
  out.target = base_gradient - out.gradient_target;
  result.rigidity_after = rigidity_energy(mesh, uv, s, rho);
  return out;
}

}  // namespace quadcover
