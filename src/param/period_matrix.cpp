#include "param/period_matrix.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace quadcover {

SparseJumpField unit_jump_field(const Mesh& mesh, const CoverCut& cut, int path) {
  JumpScratch scratch;
  return unit_jump_field(mesh, cut, cut_fans(mesh, cut), path, scratch);
}

SparseJumpField unit_jump_field(const Mesh& mesh, const CoverCut& cut, const CutFans& fans, int path,
                                JumpScratch& scratch) {
  Eigen::VectorXcd& c = scratch.c;
  Eigen::MatrixX3cd& sigma = scratch.sigma;
  if (c.size() != mesh.num_edges()) c = Eigen::VectorXcd::Zero(mesh.num_edges());
  if (sigma.rows() != mesh.num_faces()) sigma = Eigen::MatrixX3cd::Zero(mesh.num_faces(), 3);
  c[cut.path_edge[path]] = 1;
  complete_translations(mesh, cut, fans, c);
  SparseJumpField s;
  std::vector<int> moved;  // the fans written
  for (int k = 0; k < static_cast<int>(fans.vertices.size()); ++k) {
    if (!moves_fan(cut, fans, c, k)) continue;  // 0 on the whole fan
    write_fan_jump(mesh, cut, fans, c, k, sigma);
    moved.push_back(k);
    for (const auto& corner : mesh.fan(fans.vertices[k])) s.support.push_back(corner.face);
  }
  std::sort(s.support.begin(), s.support.end());
  s.support.erase(std::unique(s.support.begin(), s.support.end()), s.support.end());
  std::erase_if(s.support, [&](int f) {
    return sigma(f, 0) == Complex(0) && sigma(f, 1) == Complex(0) && sigma(f, 2) == Complex(0);
  });
  // ∇σ on the support only.
  s.X.resize(s.support.size());
  s.Y.resize(s.support.size());
  for (std::size_t k = 0; k < s.support.size(); ++k) std::tie(s.X[k], s.Y[k]) = face_gradient(mesh, sigma, s.support[k]);
  // Back to zero for the next path: the translations written and the fans' faces.
  c[cut.path_edge[path]] = 0;
  for (const int k : fans.elimination) c[cut.graph.parent_edge[fans.vertices[k]]] = 0;
  for (const int k : moved)
    for (const auto& corner : mesh.fan(fans.vertices[k])) sigma(corner.face, corner.corner) = 0;
  return s;
}

namespace {

/// ⟨Σ_a, Σ_b⟩ and ⟨Σ_a, iΣ_b⟩ (iΣ = (−Y, X)) of two sparse jump fields: merge of the sorted supports.
std::pair<double, double> sparse_inner(const Eigen::VectorXd& A, const SparseJumpField& s, const SparseJumpField& t) {
  double same = 0, turned = 0;
  std::size_t i = 0, k = 0;
  while (i < s.support.size() && k < t.support.size()) {
    if (s.support[i] < t.support[k]) {
      ++i;
    } else if (t.support[k] < s.support[i]) {
      ++k;
    } else {
      const double a = A[s.support[i]];
      same += a * std::real(std::conj(s.X[i]) * t.X[k] + std::conj(s.Y[i]) * t.Y[k]);
      turned += a * std::real(-std::conj(s.X[i]) * t.Y[k] + std::conj(s.Y[i]) * t.X[k]);
      ++i, ++k;
    }
  }
  return {same, turned};
}

/// The right-hand side b_j = ⟨∇φ_p, Σ_j⟩ (HarmonicCorrection::rhs) as its non-zero entries, sorted by vertex.
struct SparseRhs {
  std::vector<int> vertex;
  std::vector<Complex> value;
};

/// Rows a0..a1 − 1 of P and their Im rows m + a: one solve for the block's right-hand sides.
void add_period_rows(const Mesh& mesh, const HarmonicCorrection& correction, const std::vector<SparseJumpField>& sigma,
                     const std::vector<SparseRhs>& rhs, int a0, int a1, Eigen::MatrixXd& P) {
  const int m = static_cast<int>(sigma.size());
  const Eigen::VectorXd& A = mesh.face_areas();
  // 𝔏̄ u_a = b_a for the paths of the block (kernel pins: u_p = 0).
  Eigen::MatrixXcd B = Eigen::MatrixXcd::Zero(mesh.num_vertices(), a1 - a0);
  for (int a = a0; a < a1; ++a)
    for (std::size_t k = 0; k < rhs[a].vertex.size(); ++k) B(rhs[a].vertex[k], a - a0) = rhs[a].value[k];
  const Eigen::MatrixXcd U = correction.solve(std::move(B));
  // P_ab = ⟨H_a, Σ_b⟩ with H_a = Σ_a − ∇u_a and ⟨∇u_a, Σ_b⟩ = Re(u_aᴴ b_b) (b_b is ⟨∇φ_p, Σ_b⟩ per vertex, the
  // gauge factors i^λ cancel): no dense field per path, only the sparse supports. The Im rows use
  // i·H_a = (−H¹, H⁰) and b(iΣ) = i·b(Σ).
  tbb::parallel_for(a0, a1, [&](int a) {
    const auto u = U.col(a - a0);
    for (int b = 0; b < m; ++b) {
      auto [same, turned] = sparse_inner(A, sigma[a], sigma[b]);  // ⟨Σ_a, Σ_b⟩, ⟨Σ_a, iΣ_b⟩
      Complex ub = 0;                                             // u_aᴴ b_b
      const SparseRhs& r = rhs[b];
      for (std::size_t k = 0; k < r.vertex.size(); ++k) ub += std::conj(u[r.vertex[k]]) * r.value[k];
      same -= ub.real();    // − Re(u_aᴴ b_b)
      turned += ub.imag();  // − Re(u_aᴴ i b_b) = + Im(u_aᴴ b_b)
      P(a, b) = same;
      P(m + a, m + b) = same;  // ⟨iH_a, iΣ_b⟩ = ⟨H_a, Σ_b⟩
      P(a, m + b) = turned;    // ⟨H_a, iΣ_b⟩
      P(m + a, b) = -turned;   // ⟨iH_a, Σ_b⟩ = −⟨H_a, iΣ_b⟩
    }
  });
}

}  // namespace

int period_block_columns(int num_vertices) {
  constexpr double kBlockBytes = 32 << 20;
  const double fit = kBlockBytes / (static_cast<double>(sizeof(Complex)) * std::max(num_vertices, 1));
  return static_cast<int>(std::clamp(fit, 4.0, 32.0));
}

PeriodMatrix period_matrix(const Mesh& mesh, const CoverCut& cut, const HarmonicCorrection& correction,
                           int block_size, const std::function<bool()>& stop) {
  if (block_size <= 0) block_size = period_block_columns(mesh.num_vertices());
  PeriodMatrix pm;
  for (int j = 0; j < cut.num_paths(); ++j)
    if (cut.dependent_path[cut.path_component[j]] != j) pm.paths.push_back(j);
  const int m = static_cast<int>(pm.paths.size());
  pm.P = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  if (m == 0) return pm;

  // Σ_j sparse, and b_j = ⟨∇φ_p, Σ_j⟩ sparse (the vertices of supp Σ_j).
  std::vector<SparseJumpField> sigma(static_cast<std::size_t>(m));
  std::vector<SparseRhs> rhs(static_cast<std::size_t>(m));
  const CutFans fans = cut_fans(mesh, cut);
  tbb::enumerable_thread_specific<JumpScratch> scratch;
  tbb::parallel_for(0, m, [&](int a) {
    sigma[a] = unit_jump_field(mesh, cut, fans, pm.paths[a], scratch.local());
    const Eigen::VectorXcd b = correction.rhs(sigma[a].support, sigma[a].X, sigma[a].Y);
    SparseRhs& r = rhs[a];
    for (int f : sigma[a].support)
      for (int k = 0; k < 3; ++k) r.vertex.push_back(mesh.F()(f, k));
    std::sort(r.vertex.begin(), r.vertex.end());
    r.vertex.erase(std::unique(r.vertex.begin(), r.vertex.end()), r.vertex.end());
    r.value.reserve(r.vertex.size());
    for (int p : r.vertex) r.value.push_back(b[p]);
  });
  for (const SparseJumpField& s : sigma) pm.sigma_support += static_cast<long long>(s.support.size());

  // The blocks as many at once as there are threads (each solve has its own workspace, calculus/sparse_cholesky.h),
  // the stop asked on this thread between rounds.
  const int blocks = (m + block_size - 1) / block_size;
  const int at_once = std::max(1, tbb::this_task_arena::max_concurrency());
  for (int first = 0; first < blocks; first += at_once) {
    if (stop && stop()) return PeriodMatrix{};
    tbb::parallel_for(first, std::min(blocks, first + at_once), [&](int block) {
      const int a0 = block * block_size;
      add_period_rows(mesh, correction, sigma, rhs, a0, std::min(m, a0 + block_size), pm.P);
    });
  }
  const double scale = std::max(pm.P.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  pm.asymmetry = (pm.P - pm.P.transpose()).cwiseAbs().maxCoeff() / scale;
  pm.P = 0.5 * (pm.P + pm.P.transpose()).eval();
  return pm;
}

}  // namespace quadcover
