#include "field/singularity_split.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "field/relocation.h"

namespace quadcover {

namespace {

// The other endpoint of the edge opposite corner c.corner + 2 in the fan of v (ring order).
int fan_neighbor(const Mesh& mesh, int v, const Mesh::FanCorner& c) {
  const int e = mesh.FE()(c.face, (c.corner + 1) % 3);
  return mesh.E()(e, 0) == v ? mesh.E()(e, 1) : mesh.E()(e, 0);
}

// Vertices by breadth-first rings around v (v excluded), each ring in fan order of the vertex it was reached from,
// until `enough` of them satisfy `eligible` or `max_rings` rings were added. Also returns how many rings were used.
template <class Eligible>
std::vector<int> ring_candidates(const Mesh& mesh, int v, int enough, int max_rings, std::vector<char>& seen,
                                 Eligible&& eligible, std::vector<int>& region, int& rings) {
  std::vector<int> frontier{v}, candidates;
  rings = 0;
  region.assign(1, v);
  seen[static_cast<std::size_t>(v)] = 1;
  for (int ring = 0; ring < max_rings && static_cast<int>(candidates.size()) < enough && !frontier.empty(); ++ring) {
    std::vector<int> next;
    ++rings;
    for (int u : frontier)
      for (const auto& c : mesh.fan(u)) {
        const int w = fan_neighbor(mesh, u, c);
        if (seen[static_cast<std::size_t>(w)]) continue;
        seen[static_cast<std::size_t>(w)] = 1;
        next.push_back(w);
        region.push_back(w);
        if (eligible(w)) candidates.push_back(w);
      }
    frontier = std::move(next);
  }
  // One more ring for the singularities to keep away from (not candidates).
  for (int u : frontier)
    for (const auto& c : mesh.fan(u)) {
      const int w = fan_neighbor(mesh, u, c);
      if (!seen[static_cast<std::size_t>(w)]) {
        seen[static_cast<std::size_t>(w)] = 1;
        region.push_back(w);
      }
    }
  for (int w : region) seen[static_cast<std::size_t>(w)] = 0;
  return candidates;
}

double distance(const Mesh& mesh, int a, int b) { return (mesh.V().row(a) - mesh.V().row(b)).norm(); }

// Smallest distance between two of `set`, and from `set` to `others` (infinity if there is no pair).
std::pair<double, double> spacing(const Mesh& mesh, const std::vector<int>& set, const std::vector<int>& others) {
  double inner = std::numeric_limits<double>::infinity(), outer = inner;
  for (std::size_t i = 0; i < set.size(); ++i) {
    for (std::size_t j = i + 1; j < set.size(); ++j) inner = std::min(inner, distance(mesh, set[i], set[j]));
    for (int o : others) outer = std::min(outer, distance(mesh, set[i], o));
  }
  return {inner, outer};
}

// `count` of the 1-ring candidates (in fan order) evenly spaced around v: for every start s the ones at positions
// s + j·r/count; the start whose targets lie farthest apart wins, then the one farthest from `others`, then the
// lowest s (differences below 1e-9 relative count as ties).
std::vector<int> spread_around(const Mesh& mesh, const std::vector<int>& ring, int count,
                               const std::vector<int>& others) {
  const int r = static_cast<int>(ring.size());
  std::vector<int> best, set(static_cast<std::size_t>(count));
  std::pair<double, double> best_score{-1, -1};
  auto better = [](double a, double b) { return a > b * (1 + 1e-9) + 1e-300; };
  for (int s = 0; s < r; ++s) {
    for (int j = 0; j < count; ++j)
      set[static_cast<std::size_t>(j)] = ring[static_cast<std::size_t>((s + static_cast<long>(j) * r / count) % r)];
    const auto score = spacing(mesh, set, others);
    if (best.empty() || better(score.first, best_score.first) ||
        (!better(best_score.first, score.first) && better(score.second, best_score.second))) {
      best = set;
      best_score = score;
    }
  }
  return best;
}

// Farthest-point sampling of `count` candidates: each next one is the farthest from `others` and those chosen so
// far (ties: candidate order).
std::vector<int> farthest_points(const Mesh& mesh, const std::vector<int>& candidates, int count,
                                 const std::vector<int>& others) {
  std::vector<double> dist(candidates.size(), std::numeric_limits<double>::infinity());
  auto push_away = [&](int p) {
    for (std::size_t i = 0; i < candidates.size(); ++i) dist[i] = std::min(dist[i], distance(mesh, candidates[i], p));
  };
  for (int o : others) push_away(o);
  std::vector<char> taken(candidates.size(), 0);
  std::vector<int> chosen;
  for (int k = 0; k < count; ++k) {
    std::size_t best = candidates.size();
    for (std::size_t i = 0; i < candidates.size(); ++i)
      if (!taken[i] && (best == candidates.size() || dist[i] > dist[best])) best = i;
    taken[best] = 1;
    chosen.push_back(candidates[best]);
    push_away(candidates[best]);
  }
  return chosen;
}

}  // namespace

std::vector<QuarterMove> plan_singularity_split(const Mesh& mesh, const Eigen::VectorXi& quarter_index,
                                                int min_quarters) {
  const int nv = mesh.num_vertices();
  if (quarter_index.size() != nv) throw std::invalid_argument("plan_singularity_split: #V quarter indices expected");
  Eigen::VectorXi q = quarter_index;
  std::vector<char> targeted(static_cast<std::size_t>(nv), 0), seen(static_cast<std::size_t>(nv), 0);
  std::vector<QuarterMove> moves;
  std::vector<int> region;
  constexpr int kMaxRings = 8;
  for (int v = 0; v < nv; ++v) {
    const int count = std::abs(q[v]);
    if (count < std::max(2, min_quarters) || mesh.is_boundary_vertex(v)) continue;
    const int sign = q[v] > 0 ? 1 : -1;
    auto eligible = [&](int w) {
      return !mesh.is_boundary_vertex(w) && q[w] == 0 && !targeted[static_cast<std::size_t>(w)];
    };
    int rings = 0;
    const std::vector<int> candidates = ring_candidates(mesh, v, count, kMaxRings, seen, eligible, region, rings);
    if (static_cast<int>(candidates.size()) < count) continue;  // nowhere to go (tiny mesh): leave it
    // Keep away from the other singularities near v and from the targets chosen so far.
    std::vector<int> keep_away;
    for (int w : region)
      if (w != v && (q[w] != 0 || targeted[static_cast<std::size_t>(w)])) keep_away.push_back(w);
    const std::vector<int> chosen = rings == 1 ? spread_around(mesh, candidates, count, keep_away)
                                               : farthest_points(mesh, candidates, count, keep_away);
    for (int w : chosen) {
      targeted[static_cast<std::size_t>(w)] = 1;
      moves.push_back({v, w, sign});
      q[v] -= sign;
      q[w] += sign;
    }
  }
  return moves;
}

int apply_quarter_moves(const Mesh& mesh, const std::vector<QuarterMove>& moves, Eigen::VectorXi& matching) {
  int changed = 0;
  for (const QuarterMove& m : moves) {
    // (5.2.2): the matching changes along the path move the quarter; intermediate vertices are unchanged.
    for (const MatchingChange& c : relocation_changes(mesh, relocation_path(mesh, m.from, m.to), m.quarters)) {
      matching[c.edge] += c.delta;
      ++changed;
    }
  }
  return changed;
}

}  // namespace quadcover
