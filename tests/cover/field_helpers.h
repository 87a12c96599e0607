#pragma once
// Frame fields generated inside the cover/param tests (independent of the field stage): random and smooth cross
// fields with the initial matching of rule (5.1) computed from Mesh::edge_transport, and frame fields whose
// matching is a pure gauge change (trivial holonomy, no branch points).
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "field/frame_field.h"
#include "mesh/mesh.h"

namespace quadcover::testing {

/// Matching (5.1): m_e = round(2∠_e/π), ∠_e = arg(X_t / (ρ_e X_s)); 0 on boundary edges.
inline Eigen::VectorXi matching_51(const Mesh& mesh, const Eigen::VectorXcd& X) {
  Eigen::VectorXi m = Eigen::VectorXi::Zero(mesh.num_edges());
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    if (s < 0 || t < 0) continue;
    const double angle = std::arg(X[t] / (mesh.edge_transport()[e] * X[s]));
    m[e] = static_cast<int>(std::lround(2 * angle / std::numbers::pi));
  }
  return m;
}

/// Cross field (Y = iX) of unit random directions with the (5.1) matching: many branch points.
inline FrameField random_cross_field(const Mesh& mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  FrameField field;
  field.X.resize(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) field.X[f] = std::polar(1.0, angle(rng));
  field.Y = Complex(0, 1) * field.X;
  field.matching = matching_51(mesh, field.X);
  return field;
}

/// Smooth cross field: the projection of a fixed 3D direction d (plus a small tilt where it degenerates) onto each
/// face, with the (5.1) matching; branch points are few and isolated.
inline FrameField smooth_cross_field(const Mesh& mesh, const Eigen::Vector3d& d = Eigen::Vector3d(0.3, 0.2, 1.0)) {
  FrameField field;
  field.X.resize(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    Complex z = mesh.to_local(f, d.normalized());
    if (std::abs(z) < 1e-3) z = mesh.to_local(f, Eigen::Vector3d(1, 0, 0));
    field.X[f] = z / std::abs(z);
  }
  field.Y = Complex(0, 1) * field.X;
  field.matching = matching_51(mesh, field.X);
  return field;
}

/// A frame field with random (non-orthogonal) frames and a random matching (integers in [-3, 3]).
inline FrameField random_frame_field(const Mesh& mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::uniform_int_distribution<int> mm(-3, 3);
  FrameField field;
  field.X.resize(mesh.num_faces());
  field.Y.resize(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    field.X[f] = Complex(g(rng), g(rng));
    field.Y[f] = Complex(g(rng), g(rng));
  }
  field.matching = Eigen::VectorXi::Zero(mesh.num_edges());
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (!mesh.is_boundary_edge(e)) field.matching[e] = mm(rng);
  return field;
}

/// Matching of a pure gauge change: m_e = r_s - r_t for random per-face quarter turns r (trivial holonomy).
inline Eigen::VectorXi gauge_matching(const Mesh& mesh, const Eigen::VectorXi& r) {
  Eigen::VectorXi m = Eigen::VectorXi::Zero(mesh.num_edges());
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (!mesh.is_boundary_edge(e)) m[e] = r[mesh.EF()(e, 0)] - r[mesh.EF()(e, 1)];
  return m;
}

/// Matching with prescribed isolated branch points: starting from `m`, for every pair (a, b) adds δ on the edges of a
/// shortest vertex path a -> b (with the edge's orientation), which changes the quarter index by +δ at a and -δ at b
/// and leaves every other vertex unchanged.
inline Eigen::VectorXi add_branch_pairs(const Mesh& mesh, Eigen::VectorXi m,
                                        const std::vector<std::pair<int, int>>& pairs, int delta) {
  std::vector<std::vector<std::pair<int, int>>> adj(mesh.num_vertices());
  for (int e = 0; e < mesh.num_edges(); ++e) {
    adj[mesh.E()(e, 0)].push_back({mesh.E()(e, 1), e});
    adj[mesh.E()(e, 1)].push_back({mesh.E()(e, 0), e});
  }
  for (const auto& [a, b] : pairs) {
    std::vector<int> via(mesh.num_vertices(), -2);
    std::vector<int> queue{a};
    via[a] = -1;
    for (std::size_t i = 0; i < queue.size() && via[b] == -2; ++i)
      for (const auto& [w, e] : adj[queue[i]])
        if (via[w] == -2 && !mesh.is_boundary_edge(e)) {
          via[w] = e;
          queue.push_back(w);
        }
    for (int v = b; v != a;) {
      const int e = via[v];
      const int u = mesh.E()(e, 0) == v ? mesh.E()(e, 1) : mesh.E()(e, 0);  // path runs u -> v
      m[e] += mesh.E()(e, 0) == u ? delta : -delta;
      v = u;
    }
  }
  return m;
}

}  // namespace quadcover::testing
