#include "metrics/param_quality.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "param/seams.h"
#include "quad/transitions.h"

namespace quadcover {

double arap_density(const Eigen::Matrix2d& J) {
  const double a = J(0, 0), b = J(0, 1), c = J(1, 0), d = J(1, 1);
  // max_θ tr(R_θᵀ J) = |(a + d, c − b)|
  const double v = J.squaredNorm() + 2 - 2 * std::hypot(a + d, c - b);
  return 0.5 * std::max(0.0, v);
}

Eigen::Matrix2d map_jacobian(const Mesh& mesh, const Eigen::MatrixX3cd& uv, int f) {
  const Complex p1 = mesh.corner_local()(f, 1) - mesh.corner_local()(f, 0);
  const Complex p2 = mesh.corner_local()(f, 2) - mesh.corner_local()(f, 0);
  const Complex u1 = uv(f, 1) - uv(f, 0), u2 = uv(f, 2) - uv(f, 0);
  Eigen::Matrix2d P, U;
  P << p1.real(), p2.real(), p1.imag(), p2.imag();
  U << u1.real(), u2.real(), u1.imag(), u2.imag();
  return U * P.inverse();  // J P = U
}

std::vector<BranchPoint> cones_from_uv(const Eigen::MatrixX3i& F, const Eigen::MatrixX3cd& uv,
                                       const std::vector<char>& boundary) {
  std::vector<BranchPoint> cones;
  std::vector<double> angle(boundary.size(), 0.0);
  std::vector<char> used(boundary.size(), 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Complex e1 = uv(f, (k + 1) % 3) - uv(f, k), e2 = uv(f, (k + 2) % 3) - uv(f, k);
      used[F(f, k)] = 1;
      if (std::abs(e1) > 0 && std::abs(e2) > 0) angle[F(f, k)] += std::arg(e2 / e1);
    }
  for (std::size_t v = 0; v < boundary.size(); ++v) {
    if (boundary[v] || !used[v]) continue;
    const int q = static_cast<int>(std::lround((2 * std::numbers::pi - angle[v]) / (std::numbers::pi / 2)));
    if (q != 0) cones.push_back({static_cast<int>(v), q});
  }
  return cones;
}

std::vector<BranchPoint> cones_from_uv(const Eigen::MatrixX3i& F, const Eigen::MatrixX3cd& uv) {
  if (uv.rows() != F.rows() || F.rows() == 0) return {};
  std::vector<std::pair<int, int>> directed;  // every side (a, b) of every triangle, sorted
  directed.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) directed.emplace_back(F(f, k), F(f, (k + 1) % 3));
  std::sort(directed.begin(), directed.end());
  std::vector<char> boundary(static_cast<std::size_t>(F.maxCoeff()) + 1, 0);
  for (const auto& [a, b] : directed)
    if (!std::binary_search(directed.begin(), directed.end(), std::make_pair(b, a))) boundary[a] = boundary[b] = 1;
  return cones_from_uv(F, uv, boundary);
}

ParamQuality param_quality(const Mesh& mesh, const Parameterization& param, const ParamQualityOptions& options) {
  ParamQuality q;
  const int nf = mesh.num_faces();
  const Eigen::VectorXd& A = mesh.face_areas();
  std::vector<Eigen::Matrix2d> J(nf);
  for (int f = 0; f < nf; ++f) {
    J[f] = map_jacobian(mesh, param.uv, f);
    const double det = J[f].determinant();
    q.uv_area += std::abs(det) * A[f];
  }
  // Signs from the parameter areas against A_ref (param/seams.h): a triangle collapsed to round-off counts as
  // collapsed, never as a flip, and never as valid.
  const FlipReport flips = flipped_triangles(mesh, param.uv);
  q.flipped_triangles = flips.flipped;
  q.collapsed_triangles = flips.collapsed;
  q.non_positive_triangles = flips.non_positive;
  q.scale = q.uv_area > 0 ? std::sqrt(mesh.total_area() / q.uv_area) : 1.0;
  q.arap_per_face.resize(nf);
  double weighted = 0;
  for (int f = 0; f < nf; ++f) {
    q.arap_per_face[f] = arap_density(q.scale * J[f]);
    weighted += A[f] * q.arap_per_face[f];
    q.arap_max = std::max(q.arap_max, q.arap_per_face[f]);
  }
  q.arap = mesh.total_area() > 0 ? weighted / mesh.total_area() : 0;
  // area-weighted 95th percentile
  std::vector<int> order(nf);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return q.arap_per_face[x] < q.arap_per_face[y]; });
  double acc = 0;
  for (int f : order) {
    acc += A[f];
    q.arap_p95 = q.arap_per_face[f];
    if (acc >= 0.95 * mesh.total_area()) break;
  }
  q.arap_bins = options.arap_bins;
  q.arap_histogram.assign(options.arap_bins.size() + 1, 0);
  for (double v : q.arap_per_face) {
    const auto it = std::lower_bound(options.arap_bins.begin(), options.arap_bins.end(), v);
    ++q.arap_histogram[it - options.arap_bins.begin()];
  }
  q.energy_curl = param.energy_curl;
  q.energy_harmonic = param.energy_harmonic;

  // Seamlessness over interior edges.
  const bool has_rot = param.transition_rotation.size() == mesh.num_edges();
  const bool has_trans = param.transition_translation.size() == mesh.num_edges();
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    if (s < 0 || t < 0) continue;
    const Complex r = ipow(has_rot ? param.transition_rotation[e] : 0);
    const Complex c = has_trans ? param.transition_translation[e] : Complex(0, 0);
    q.max_translation_defect =
        std::max(q.max_translation_defect, std::abs(c - Complex(std::round(c.real()), std::round(c.imag()))));
    for (int j = 0; j < 2; ++j) {
      const int v = mesh.E()(e, j);
      int cs = 0, ct = 0;
      for (int k = 0; k < 3; ++k) {
        if (mesh.F()(s, k) == v) cs = k;
        if (mesh.F()(t, k) == v) ct = k;
      }
      q.max_transition_error = std::max(q.max_transition_error, std::abs(param.uv(t, ct) - (r * param.uv(s, cs) + c)));
    }
  }
  // Cone points from the parameter angle sums; a corner of each vertex for its φ.
  std::vector<char> boundary(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (int v = 0; v < mesh.num_vertices(); ++v) boundary[v] = mesh.is_boundary_vertex(v);
  std::vector<int> corner_face(mesh.num_vertices(), -1), corner_idx(mesh.num_vertices(), -1);
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) corner_face[mesh.F()(f, c)] = f, corner_idx[mesh.F()(f, c)] = c;
  for (const BranchPoint& b : cones_from_uv(mesh.F(), param.uv, boundary)) {
    ++q.branch_points_by_index[b.quarter_index];
    ++q.branch_points;
    const Complex z = param.uv(corner_face[b.vertex], corner_idx[b.vertex]);
    q.max_branch_point_offset =
        std::max(q.max_branch_point_offset, std::abs(z - Complex(std::round(z.real()), std::round(z.imag()))));
  }
  return q;
}

}  // namespace quadcover
