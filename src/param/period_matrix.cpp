#include "param/period_matrix.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace quadcover {

SparseJumpField unit_jump_field(const Mesh& mesh, const CoverCut& cut, int path) {
  Eigen::VectorXcd c = Eigen::VectorXcd::Zero(mesh.num_edges());
  c[cut.path_edge[path]] = 1;
  complete_translations(mesh, cut, c);
  const Eigen::MatrixX3cd sigma = jump_function(mesh, cut, c);
  SparseJumpField s;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (sigma(f, 0) == Complex(0) && sigma(f, 1) == Complex(0) && sigma(f, 2) == Complex(0)) continue;
    s.support.push_back(f);
  }
  // ∇σ on the support only.
  s.X.resize(s.support.size());
  s.Y.resize(s.support.size());
  for (std::size_t k = 0; k < s.support.size(); ++k) std::tie(s.X[k], s.Y[k]) = face_gradient(mesh, sigma, s.support[k]);
  return s;
}

PeriodMatrix period_matrix(const Mesh& mesh, const CoverCut& cut, const HarmonicCorrection& correction,
                           int block_size, const std::function<bool()>& stop) {
  PeriodMatrix pm;
  for (int j = 0; j < cut.num_paths(); ++j)
    if (cut.dependent_path[cut.path_component[j]] != j) pm.paths.push_back(j);
  const int m = static_cast<int>(pm.paths.size());
  pm.P = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  if (m == 0) return pm;

  std::vector<SparseJumpField> sigma(static_cast<std::size_t>(m));
  tbb::parallel_for(0, m, [&](int a) { sigma[a] = unit_jump_field(mesh, cut, pm.paths[a]); });
  for (const SparseJumpField& s : sigma) pm.sigma_support += static_cast<long long>(s.support.size());

  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  const Eigen::VectorXd& A = mesh.face_areas();
  for (int a0 = 0; a0 < m; a0 += block_size) {
    if (stop && stop()) return PeriodMatrix{};
    const int a1 = std::min(m, a0 + block_size);
    // One harmonic field H_i = Σ_i − ∇u_i per path of the block: 𝔏̄ u_i = b_i, b_i from the sparse Σ_i.
    Eigen::MatrixXcd B(nv, a1 - a0);
    for (int a = a0; a < a1; ++a) {
      FramePairs S = FramePairs::Zero(nf, 2);
      const SparseJumpField& s = sigma[a];
      for (std::size_t k = 0; k < s.support.size(); ++k) S.row(s.support[k]) << s.X[k], s.Y[k];
      B.col(a - a0) = correction.rhs(S, s.support);
    }
    const Eigen::MatrixXcd U = correction.solve(B);
    tbb::parallel_for(a0, a1, [&](int a) {
      FramePairs H = -corner_gradient(mesh, correction.corner_values(U.col(a - a0)));
      const SparseJumpField& s = sigma[a];
      for (std::size_t k = 0; k < s.support.size(); ++k) {
        H(s.support[k], 0) += s.X[k];
        H(s.support[k], 1) += s.Y[k];
      }
      // Row a (Re d_a) and row m + a (Im d_a, the field i·H_a = (−H¹, H⁰)) against every sparse Σ_b.
      for (int b = 0; b < m; ++b) {
        double same = 0, turned = 0;  // ⟨H_a, Σ_b⟩ and ⟨H_a, iΣ_b⟩
        const SparseJumpField& t = sigma[b];
        for (std::size_t k = 0; k < t.support.size(); ++k) {
          const int f = t.support[k];
          const Complex h0 = H(f, 0), h1 = H(f, 1);
          same += A[f] * std::real(std::conj(h0) * t.X[k] + std::conj(h1) * t.Y[k]);
          turned += A[f] * std::real(-std::conj(h0) * t.Y[k] + std::conj(h1) * t.X[k]);
        }
        pm.P(a, b) = same;
        pm.P(m + a, m + b) = same;   // ⟨iH_a, iΣ_b⟩ = ⟨H_a, Σ_b⟩
        pm.P(a, m + b) = turned;     // ⟨H_a, iΣ_b⟩
        pm.P(m + a, b) = -turned;    // ⟨iH_a, Σ_b⟩ = −⟨H_a, iΣ_b⟩
      }
    });
  }
  const double scale = std::max(pm.P.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  pm.asymmetry = (pm.P - pm.P.transpose()).cwiseAbs().maxCoeff() / scale;
  pm.P = 0.5 * (pm.P + pm.P.transpose()).eval();
  return pm;
}

}  // namespace quadcover
