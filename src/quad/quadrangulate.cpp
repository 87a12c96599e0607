#include "quad/quadrangulate.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <unordered_set>

namespace quadcover {

namespace {

using Key = unsigned long long;
Key edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<Key>(static_cast<unsigned>(a)) << 32) | static_cast<unsigned>(b);
}

class Splitter {
 public:
  Splitter(const Eigen::MatrixX3d& V, const std::unordered_map<Key, int>& edge_uses) : V_(V), uses_(edge_uses) {}

  // Best split of polygon P (even size) into quads: cost Σ (angle − π/2)², quads appended to `out`. false if none.
  bool split(const std::vector<int>& P, std::vector<std::vector<int>>& out) {
    normal_ = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < P.size(); ++i)  // Newell normal of the polygon
      normal_ += Eigen::Vector3d(V_.row(P[i])).cross(Eigen::Vector3d(V_.row(P[(i + 1) % P.size()])));
    if (normal_.norm() == 0) return false;
    std::vector<std::vector<int>> quads;
    const double c = best(P, quads);
    if (!std::isfinite(c)) return false;
    out.insert(out.end(), quads.begin(), quads.end());
    return true;
  }

 private:
  const Eigen::MatrixX3d& V_;
  const std::unordered_map<Key, int>& uses_;
  Eigen::Vector3d normal_;

  double quad_cost(const std::vector<int>& q) const {
    double cost = 0;
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d a = V_.row(q[(i + 3) % 4]), b = V_.row(q[i]), c = V_.row(q[(i + 1) % 4]);
      const Eigen::Vector3d u = a - b, w = c - b;
      if ((b - a).cross(c - b).dot(normal_) <= 0) return INFINITY;  // reflex or flat corner
      const double angle = std::atan2(u.cross(w).norm(), u.dot(w));
      cost += (angle - std::numbers::pi / 2) * (angle - std::numbers::pi / 2);
    }
    return cost;
  }
  bool is_edge(int a, int b) const { return uses_.count(edge_key(a, b)) > 0; }

  // P[0..n): the quad holding side P0-P1 is (P0, P1, Pa, Pb); the three gaps are sides (size 2) or even polygons.
  double best(const std::vector<int>& P, std::vector<std::vector<int>>& quads) {
    const int n = static_cast<int>(P.size());
    if (n == 2) return 0;
    double best_cost = INFINITY;
    for (int a = 2; a < n; a += 2)
      for (int b = a + 1; b < n; b += 2) {
        if ((a != 2 && is_edge(P[1], P[a])) || (b != a + 1 && is_edge(P[a], P[b])) ||
            (b != n - 1 && is_edge(P[b], P[0])))
          continue;  // a diagonal that is an edge elsewhere would make that edge non-manifold
        std::vector<std::vector<int>> qs = {{P[0], P[1], P[a], P[b]}};
        double cost = quad_cost(qs[0]);
        if (!std::isfinite(cost) || cost >= best_cost) continue;
        std::vector<int> g1(P.begin() + 1, P.begin() + a + 1), g2(P.begin() + a, P.begin() + b + 1),
            g3(P.begin() + b, P.end());
        g3.push_back(P[0]);
        for (const auto* g : {&g1, &g2, &g3}) {
          if (g->size() == 2) continue;
          std::vector<std::vector<int>> sub;
          cost += best(*g, sub);
          if (!std::isfinite(cost) || cost >= best_cost) break;
          qs.insert(qs.end(), sub.begin(), sub.end());
        }
        if (cost < best_cost) best_cost = cost, quads.swap(qs);
      }
    return best_cost;
  }
};

}  // namespace

QuadrangulateReport quadrangulate_polygons(QuadMesh& q, int max_size) {
  QuadrangulateReport rep;
  const int nf = q.num_faces();
  std::unordered_map<Key, int> uses;
  std::unordered_map<Key, std::pair<int, int>> faces_of;  // undirected edge -> (first face, second face)
  for (int f = 0; f < nf; ++f) {
    const auto& F = q.faces[f];
    for (std::size_t i = 0; i < F.size(); ++i) {
      const Key k = edge_key(F[i], F[(i + 1) % F.size()]);
      auto [it, fresh] = faces_of.emplace(k, std::pair{f, -1});
      if (!fresh) it->second.second = f;
      ++uses[k];
    }
  }
  auto interior = [&](int f) {
    const auto& F = q.faces[f];
    for (std::size_t i = 0; i < F.size(); ++i)
      if (uses[edge_key(F[i], F[(i + 1) % F.size()])] != 2) return false;
    return true;
  };
  std::vector<char> consumed(nf, 0);
  std::vector<std::vector<int>> added;
  // The new quads of polygon P: its sides keep their two faces, each diagonal gets the two quads beside it.
  auto commit = [&](const std::vector<int>& P, const std::vector<std::vector<int>>& quads) {
    std::unordered_set<Key> sides;
    for (std::size_t i = 0; i < P.size(); ++i) sides.insert(edge_key(P[i], P[(i + 1) % P.size()]));
    for (const auto& Q : quads)
      for (int i = 0; i < 4; ++i)
        if (!sides.count(edge_key(Q[i], Q[(i + 1) % 4]))) uses[edge_key(Q[i], Q[(i + 1) % 4])] = 2;
    added.insert(added.end(), quads.begin(), quads.end());
  };
  Splitter splitter(q.V, uses);
  // Even polygons.
  for (int f = 0; f < nf; ++f) {
    const int n = static_cast<int>(q.faces[f].size());
    if (n == 4 || n % 2 || n > max_size || !interior(f)) continue;
    std::vector<std::vector<int>> quads;
    if (!splitter.split(q.faces[f], quads)) continue;
    consumed[f] = 1;
    commit(q.faces[f], quads);
    ++rep.split_polygons;
  }
  // Odd pairs sharing exactly one edge: merge across it, then split (or keep the quad).
  for (int f = 0; f < nf; ++f) {
    const auto& F = q.faces[f];
    const int n = static_cast<int>(F.size());
    if (consumed[f] || n % 2 == 0 || n > max_size || !interior(f)) continue;
    for (int i = 0; i < n && !consumed[f]; ++i) {
      const int a = F[i], b = F[(i + 1) % n];
      const auto [f1, f2] = faces_of[edge_key(a, b)];
      const int g = f1 == f ? f2 : f1;
      if (g < 0 || g == f || consumed[g] || q.faces[g].size() % 2 == 0 || !interior(g)) continue;
      const auto& G = q.faces[g];
      const int m = static_cast<int>(G.size());
      if (n + m - 2 > max_size) continue;
      int shared = 0;
      for (int u : F)
        shared += static_cast<int>(std::count(G.begin(), G.end(), u));
      if (shared != 2) continue;  // more contact than the edge a-b: merging would pinch
      // F = [.., a, b, ..], G = [.., b, a, ..]: merged = F from b round to a, then G after a up to before b.
      std::vector<int> merged;
      for (int k = 0; k < n; ++k) merged.push_back(F[(i + 1 + k) % n]);
      const int ja = static_cast<int>(std::find(G.begin(), G.end(), a) - G.begin());
      for (int k = 1; k < m - 1; ++k) merged.push_back(G[(ja + k) % m]);
      std::vector<std::vector<int>> quads;
      bool ok = false;
      if (merged.size() == 4) {
        ok = true;
        quads.push_back(merged);
        Eigen::Vector3d nrm = Eigen::Vector3d::Zero();
        for (int k = 0; k < 4; ++k)
          nrm += Eigen::Vector3d(q.V.row(merged[k])).cross(Eigen::Vector3d(q.V.row(merged[(k + 1) % 4])));
        for (int k = 0; k < 4 && ok; ++k) {
          const Eigen::Vector3d p0 = q.V.row(merged[(k + 3) % 4]), p1 = q.V.row(merged[k]), p2 = q.V.row(merged[(k + 1) % 4]);
          ok = (p1 - p0).cross(p2 - p1).dot(nrm) > 0;
        }
      } else {
        ok = splitter.split(merged, quads);
      }
      if (!ok) continue;
      uses.erase(edge_key(a, b));  // the shared edge goes away
      consumed[f] = consumed[g] = 1;
      commit(merged, quads);
      ++rep.merged_pairs;
      if (merged.size() > 4) ++rep.split_polygons;
    }
  }
  if (added.empty()) return rep;
  std::vector<std::vector<int>> faces;
  faces.reserve(nf + added.size());
  for (int f = 0; f < nf; ++f)
    if (!consumed[f]) faces.push_back(std::move(q.faces[f]));
  for (auto& Q : added) faces.push_back(std::move(Q));
  q.faces = std::move(faces);
  return rep;
}

}  // namespace quadcover
