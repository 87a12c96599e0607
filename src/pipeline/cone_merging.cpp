#include "pipeline/cone_merging.h"

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <tuple>

#include "common/quarter_turn.h"
#include "field/indices.h"
#include "field/relocation.h"
#include "field/smoothing.h"
#include "param/density.h"
#include "param/map_development.h"
#include "param/ring_winding.h"
#include "param/seams.h"

namespace quadcover {

std::vector<ConeMerge> coincident_cone_merges(const Mesh& mesh, const Parameterization& map) {
  const Eigen::VectorXi quarter = quarter_index_of(mesh.num_vertices(), map.branch_points);
  std::vector<char> used(static_cast<std::size_t>(mesh.num_vertices()), 0);
  std::vector<ConeMerge> merges;
  std::vector<int> faces = map.diagnostics.untangling.stuck_faces;
  std::sort(faces.begin(), faces.end());
  for (const int f : faces) {
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.F()(f, c), b = mesh.F()(f, (c + 1) % 3);
      if (quarter[a] % 4 == 0 || quarter[b] % 4 == 0 || used[a] || used[b]) continue;
      const double gap = std::abs(map.uv(f, c) - map.uv(f, (c + 1) % 3));
      const int e = mesh.FE()(f, (c + 2) % 3);  // corner c to c + 1: the face edge opposite corner c + 2
      if (gap > 1e-9 || e < 0 || mesh.is_boundary_edge(e)) continue;
      const int from = std::max(a, b), into = std::min(a, b);
      merges.push_back({from, into, mod4(quarter[from])});
      used[a] = used[b] = 1;
    }
  }
  return merges;
}

namespace {

/// The vertices sharing an edge with v (the other corners of its fan's faces), ascending.
std::vector<int> sorted_neighbours(const Mesh& mesh, int v) {
  std::vector<int> out;
  for (const Mesh::FanCorner& c : mesh.fan(v))
    for (int k = 1; k < 3; ++k) out.push_back(mesh.F()(c.face, (c.corner + k) % 3));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// The first branch point q ≠ p in `around` (developed_around p) on p's point that `used` leaves free, or -1.
int coincident_partner(const Mesh& mesh, const Eigen::VectorXi& quarter, const std::vector<char>& used,
                       const std::vector<std::pair<int, Complex>>& around, int p) {
  Complex at = 0;
  for (const auto& [q, z] : around)
    if (q == p) at = z;
  for (const auto& [q, z] : around)
    if (q != p && quarter[q] % 4 != 0 && !used[q] && !mesh.is_boundary_vertex(q) &&
        std::abs(z - at) <= 1e-9 * (1 + std::abs(at)))
      return q;
  return -1;
}

}  // namespace

std::vector<ConeMerge> close_coincident_merges(const Mesh& mesh, const Parameterization& map, CoincidentReach reach,
                                               CoincidentCause cause) {
  const Eigen::VectorXi quarter = quarter_index_of(mesh.num_vertices(), map.branch_points);
  const VertexLayers layers{map.subspace.layer, map.subspace.branch};
  const Eigen::VectorXcd zero = Eigen::VectorXcd::Zero(mesh.num_vertices());
  const Eigen::VectorXi wound = map_quarter_index(mesh, map.uv);
  std::vector<char> used(static_cast<std::size_t>(mesh.num_vertices()), 0);
  std::vector<ConeMerge> merges;
  const auto wound_wrong = [&](int q) { return !mesh.is_boundary_vertex(q) && wound[q] != quarter[q]; };
  std::vector<char> folded(static_cast<std::size_t>(mesh.num_vertices()), 0);  // corners of non-positive triangles
  if (cause == CoincidentCause::AlsoFolds)
    for (const int f : flipped_triangles(mesh, map.uv).flipped_faces)
      for (int c = 0; c < 3; ++c) folded[mesh.F()(f, c)] = 1;
  const bool any_folded = std::find(folded.begin(), folded.end(), 1) != folded.end();
  // A common neighbour of p and q that is no cone and a corner of a non-positive triangle (see the header).
  const auto folded_between = [&](int p, int q) {
    const std::vector<int> a = sorted_neighbours(mesh, p), b = sorted_neighbours(mesh, q);
    std::vector<int> common;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
    return std::any_of(common.begin(), common.end(),
                       [&](int n) { return folded[n] && quarter[n] == 0 && !mesh.is_boundary_vertex(n); });
  };
  const auto merge = [&](int p, int q) {
    merges.push_back({std::max(p, q), std::min(p, q), mod4(quarter[std::max(p, q)])});
    used[p] = used[q] = 1;
  };
  const auto candidate = [&](int p) {
    return quarter[p] % 4 != 0 && !used[p] && !mesh.is_boundary_vertex(p) && !mesh.fan(p).empty();
  };
  // Near: a pair within kNearRings of a wrongly wound vertex, or with a folded common neighbour.
  for (int p = 0; p < mesh.num_vertices(); ++p) {
    if (!candidate(p)) continue;
    const auto near = developed_around(mesh, layers, map.uv, zero, p, kNearRings);
    const bool wound_near =
        std::any_of(near.begin(), near.end(), [&](const auto& qz) { return wound_wrong(qz.first); });
    if (!wound_near && !any_folded) continue;  // no partner search where neither cause can hold
    if (const int q = coincident_partner(mesh, quarter, used, near, p); q >= 0 && (wound_near || folded_between(p, q)))
      merge(p, q);
  }
  if (reach == CoincidentReach::Near) return merges;
  for (int p = 0; p < mesh.num_vertices(); ++p) {
    if (!candidate(p) || !wound_wrong(p)) continue;
    const auto around = developed_around(mesh, layers, map.uv, zero, p, kFarRings);
    if (const int q = coincident_partner(mesh, quarter, used, around, p); q >= 0) merge(p, q);
  }
  return merges;
}

namespace {

/// The first vertex within kWoundRings rings of c (breadth first, neighbours ascending) for which `fits` holds, or -1.
template <class Fits>
int nearest_within_rings(const Mesh& mesh, int c, Fits fits) {
  constexpr int kWoundRings = 3;
  std::vector<int> ring{c}, seen{c};
  for (int k = 0; k < kWoundRings; ++k) {
    std::vector<int> next;
    for (int v : ring)
      for (int n : sorted_neighbours(mesh, v)) {
        if (std::find(seen.begin(), seen.end(), n) != seen.end()) continue;
        seen.push_back(n);
        if (fits(n)) return n;
        next.push_back(n);
      }
    ring.swap(next);
  }
  return -1;
}

}  // namespace

std::vector<ConeMerge> wound_cone_moves(const Mesh& mesh, const Parameterization& map) {
  const int nv = mesh.num_vertices();
  const Eigen::VectorXi target = quarter_index_of(nv, map.branch_points);
  const Eigen::VectorXi excess = map_quarter_index(mesh, map.uv) - target;  // ±4: one turn off
  std::vector<char> used(static_cast<std::size_t>(nv), 0);
  std::vector<ConeMerge> moves;
  for (int c = 0; c < nv; ++c) {
    if (target[c] % 4 == 0 || std::abs(excess[c]) != 4 || mesh.is_boundary_vertex(c) || used[c]) continue;
    const int n = nearest_within_rings(mesh, c, [&](int v) {
      return target[v] == 0 && excess[v] == -excess[c] && !mesh.is_boundary_vertex(v) && !used[v];
    });
    if (n < 0) continue;
    moves.push_back({c, n, mod4(target[c])});
    used[c] = used[n] = 1;
  }
  return moves;
}

std::vector<ConeMerge> close_opposite_cone_merges(const Mesh& mesh, const std::vector<BranchPoint>& points,
                                                  double max_distance, const std::vector<double>& component_density) {
  const Eigen::VectorXi quarter = quarter_index_of(mesh.num_vertices(), points);
  const Eigen::VectorXd rho = vertex_density(mesh, component_density);
  struct Pair {
    double distance;
    int p, q;
  };
  std::vector<Pair> pairs;
  for (const BranchPoint& b : points)
    for (const auto& [q, d] : relocation_reach(mesh, b.vertex, max_distance / rho[b.vertex]))
      if (q > b.vertex && quarter[q] == -b.quarter_index && !mesh.is_boundary_vertex(q))
        pairs.push_back({d, b.vertex, q});
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    return std::tie(a.distance, a.p, a.q) < std::tie(b.distance, b.p, b.q);
  });
  std::vector<char> used(static_cast<std::size_t>(mesh.num_vertices()), 0);
  std::vector<ConeMerge> merges;
  for (const Pair& pair : pairs) {
    if (used[pair.p] || used[pair.q]) continue;
    merges.push_back({pair.q, pair.p, mod4(quarter[pair.q])});
    used[pair.p] = used[pair.q] = 1;
  }
  return merges;
}

FrameField merge_cones(const Mesh& mesh, const FrameFieldResult& stage, const FrameField& field, double lambda,
                       const std::vector<ConeMerge>& merges) {
  FrameSmoother smoother(mesh, field, stage.stability, stage.trusted, stage.constrained, lambda);
  for (const ConeMerge& m : merges)
    for (const MatchingChange& change : relocation_changes(mesh, relocation_path(mesh, m.from, m.into), m.quarters))
      smoother.change_matching(change.edge, change.delta);
  return smoother.rotated(smoother.solve());
}

}  // namespace quadcover
