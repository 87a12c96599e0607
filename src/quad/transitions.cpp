#include "quad/transitions.h"

#include <cmath>

#include "quad/extract_quads.h"

namespace quadcover {

TransitionFit fit_transitions(const Mesh& mesh, const Eigen::MatrixX3cd& uv) {
  const int ne = mesh.num_edges();
  TransitionFit fit;
  fit.rotation = Eigen::VectorXi::Zero(ne);
  fit.translation = Eigen::VectorXcd::Zero(ne);
  fit.residual = Eigen::VectorXd::Zero(ne);
  fit.integer_defect = Eigen::VectorXd::Zero(ne);
  for (int e = 0; e < ne; ++e) {
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    if (s < 0 || t < 0) continue;
    const int a = mesh.E()(e, 0), b = mesh.E()(e, 1);
    const Complex sa = uv(s, mesh.corner_of(s, a)), sb = uv(s, mesh.corner_of(s, b));
    const Complex ta = uv(t, mesh.corner_of(t, a)), tb = uv(t, mesh.corner_of(t, b));
    // φ_t - i^k φ_s must be the same constant c at both endpoints: the edge vector rotates by i^k.
    int best_k = 0;
    double best = INFINITY;
    for (int k = 0; k < 4; ++k) {
      const double r = std::abs((tb - ta) - ipow(k) * (sb - sa));
      if (r < best) best = r, best_k = k;
    }
    const Complex ca = ta - ipow(best_k) * sa, cb = tb - ipow(best_k) * sb;
    const Complex c = 0.5 * (ca + cb);
    fit.rotation[e] = best_k;
    fit.translation[e] = c;
    fit.residual[e] = std::max(std::abs(ca - c), std::abs(cb - c));
    fit.integer_defect[e] = std::abs(c - Complex(std::round(c.real()), std::round(c.imag())));
  }
  return fit;
}

Parameterization parameterization_from_uv(const Mesh& mesh, const Eigen::MatrixX3cd& uv) {
  const TransitionFit fit = fit_transitions(mesh, uv);
  Parameterization p;
  p.uv = uv;
  p.transition_rotation = fit.rotation;
  p.transition_translation.resize(mesh.num_edges());
  p.cut_edges = Eigen::VectorXi::Zero(mesh.num_edges());
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const Complex c = fit.translation[e];
    p.transition_translation[e] = {std::round(c.real()), std::round(c.imag())};
    p.cut_edges[e] = (fit.rotation[e] != 0 || std::abs(p.transition_translation[e]) > 0) ? 1 : 0;
  }
  return p;
}

}  // namespace quadcover
