#include "quad/quadrangulate.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "common/union_find.h"

namespace quadcover {

namespace {

using Key = unsigned long long;
Key edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<Key>(static_cast<unsigned>(a)) << 32) | static_cast<unsigned>(b);
}

/// Components of a polygon mesh through shared edges: per face its representative, per representative the number
/// of faces and whether some side of the component is used by one face only (open).
struct FaceComponents {
  std::vector<int> of_face, size;
  std::vector<char> open;
};
FaceComponents face_components(const QuadMesh& q) {
  const int nf = q.num_faces();
  detail::UnionFind components(nf);
  std::unordered_map<Key, std::pair<int, int>> sides;  // undirected edge -> (first face, uses)
  for (int f = 0; f < nf; ++f) {
    const auto& F = q.faces[f];
    for (std::size_t i = 0; i < F.size(); ++i) {
      auto [it, fresh] = sides.emplace(edge_key(F[i], F[(i + 1) % F.size()]), std::pair{f, 0});
      ++it->second.second;
      if (!fresh) components.unite(f, it->second.first);
    }
  }
  FaceComponents c{std::vector<int>(nf), std::vector<int>(nf, 0), std::vector<char>(nf, 0)};
  for (int f = 0; f < nf; ++f) ++c.size[c.of_face[f] = components.find(f)];
  for (const auto& [k, s] : sides)
    if (s.second == 1) c.open[c.of_face[s.first]] = 1;
  return c;
}

// F and G share exactly one edge (a→b in F, b→a in G) and no other vertex: the loop of their union, and the key of
// the edge that disappears. false otherwise (merging would pinch or fold).
bool merge_loops(const std::vector<int>& F, const std::vector<int>& G, std::vector<int>& merged, Key& removed) {
  int shared = 0;
  for (int u : F) shared += static_cast<int>(std::count(G.begin(), G.end(), u));
  if (shared != 2) return false;
  const int n = static_cast<int>(F.size()), m = static_cast<int>(G.size());
  for (int i = 0; i < n; ++i) {
    const int a = F[i], b = F[(i + 1) % n];
    const int ja = static_cast<int>(std::find(G.begin(), G.end(), a) - G.begin());
    if (ja == m || G[(ja + m - 1) % m] != b) continue;
    merged.clear();
    for (int k = 0; k < n; ++k) merged.push_back(F[(i + 1 + k) % n]);   // b round to a
    for (int k = 1; k < m - 1; ++k) merged.push_back(G[(ja + k) % m]);  // after a, up to before b
    removed = edge_key(a, b);
    return true;
  }
  return false;
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

// The state of quadrangulate_polygons: edge uses and faces, the polygons consumed and the quads that replace them.
class PolygonQuadrangulation {
 public:
  PolygonQuadrangulation(QuadMesh& q, int max_size) : q_(q), max_size_(max_size), nf_(q.num_faces()) {
    for (int f = 0; f < nf_; ++f) {
      const auto& F = q.faces[f];
      for (std::size_t i = 0; i < F.size(); ++i) {
        const Key k = edge_key(F[i], F[(i + 1) % F.size()]);
        auto [it, fresh] = faces_of_.emplace(k, std::pair{f, -1});
        if (!fresh) it->second.second = f;
        ++uses_[k];
      }
    }
    consumed_.assign(nf_, 0);
  }

  // Even polygons.
  void split_even() {
    for (int f = 0; f < nf_; ++f) {
      const int n = static_cast<int>(q_.faces[f].size());
      if (n == 4 || n % 2 || n > max_size_ || !interior(f)) continue;
      std::vector<std::vector<int>> quads;
      if (!splitter_.split(q_.faces[f], quads)) continue;
      consumed_[f] = 1;
      commit(q_.faces[f], quads);
      ++rep_.split_polygons;
    }
  }

  // Odd polygons: merged with an odd neighbour, or through one quad with an odd polygon beyond it, then split.
  void merge_odd() {
    for (int pass = 0; pass < 2; ++pass)
      for (int f = 0; f < nf_; ++f) {
        if (!usable(f, true)) continue;
        for (int g : neighbours(f)) {
          if (consumed_[f] || !usable(g, pass == 0)) continue;
          std::vector<int> m1;
          Key k1 = 0;
          if (!merge_loops(q_.faces[f], q_.faces[g], m1, k1)) continue;
          if (pass == 0) {
            take(m1, {k1}, {f, g});
            continue;
          }
          for (int h : neighbours(g)) {  // f + quad g + odd h
            std::vector<int> m2;
            Key k2 = 0;
            if (h == f || !usable(h, true) || !merge_loops(m1, q_.faces[h], m2, k2)) continue;
            if (take(m2, {k1, k2}, {f, g, h})) break;
          }
        }
      }
  }

  // Replaces the consumed faces of q by the new quads.
  QuadrangulateReport finish() {
    if (added_.empty()) return rep_;
    std::vector<std::vector<int>> faces;
    faces.reserve(nf_ + added_.size());
    for (int f = 0; f < nf_; ++f)
      if (!consumed_[f]) faces.push_back(std::move(q_.faces[f]));
    for (auto& Q : added_) faces.push_back(std::move(Q));
    q_.faces = std::move(faces);
    return rep_;
  }

 private:
  bool interior(int f) {
    const auto& F = q_.faces[f];
    for (std::size_t i = 0; i < F.size(); ++i)
      if (uses_[edge_key(F[i], F[(i + 1) % F.size()])] != 2) return false;
    return true;
  }
  // The new quads of polygon P: its sides keep their two faces, each diagonal gets the two quads beside it.
  void commit(const std::vector<int>& P, const std::vector<std::vector<int>>& quads) {
    std::unordered_set<Key> sides;
    for (std::size_t i = 0; i < P.size(); ++i) sides.insert(edge_key(P[i], P[(i + 1) % P.size()]));
    for (const auto& Q : quads)
      for (int i = 0; i < 4; ++i)
        if (!sides.count(edge_key(Q[i], Q[(i + 1) % 4]))) uses_[edge_key(Q[i], Q[(i + 1) % 4])] = 2;
    added_.insert(added_.end(), quads.begin(), quads.end());
  }
  std::vector<int> neighbours(int f) {
    std::vector<int> out;
    const auto& F = q_.faces[f];
    for (std::size_t i = 0; i < F.size(); ++i) {
      const auto [f1, f2] = faces_of_[edge_key(F[i], F[(i + 1) % F.size()])];
      const int g = f1 == f ? f2 : f1;
      if (g >= 0 && g != f && std::find(out.begin(), out.end(), g) == out.end()) out.push_back(g);
    }
    return out;
  }
  bool usable(int g, bool odd) {
    return !consumed_[g] && (q_.faces[g].size() % 2 == 1) == odd && static_cast<int>(q_.faces[g].size()) <= max_size_ &&
           interior(g);
  }
  bool take(const std::vector<int>& loop, const std::vector<Key>& removed, const std::vector<int>& from) {
    std::vector<std::vector<int>> quads;
    if (static_cast<int>(loop.size()) > max_size_ + 2 || !splitter_.split(loop, quads)) return false;
    for (Key k : removed) uses_.erase(k);
    for (int g : from) consumed_[g] = 1;
    commit(loop, quads);
    ++rep_.merged_pairs;
    if (loop.size() > 4) ++rep_.split_polygons;
    return true;
  }

  QuadMesh& q_;
  const int max_size_, nf_;
  std::unordered_map<Key, int> uses_;
  std::unordered_map<Key, std::pair<int, int>> faces_of_;  // undirected edge -> (first face, second face)
  std::vector<char> consumed_;
  std::vector<std::vector<int>> added_;
  Splitter splitter_{q_.V, uses_};
  QuadrangulateReport rep_;
};

}  // namespace

QuadrangulateReport quadrangulate_polygons(QuadMesh& q, int max_size) {
  if (q.num_quads() == q.num_faces()) return {};
  PolygonQuadrangulation run(q, max_size);
  run.split_even();
  run.merge_odd();
  return run.finish();
}

int drop_closed_debris(QuadMesh& q, int min_faces) {
  const int nf = q.num_faces();
  const FaceComponents c = face_components(q);
  std::vector<std::vector<int>> kept;
  int dropped = 0;
  for (int f = 0; f < nf; ++f) {
    const int r = c.of_face[f];
    if (!c.open[r] && c.size[r] < min_faces)
      ++dropped;
    else
      kept.push_back(std::move(q.faces[f]));
  }
  q.faces = std::move(kept);
  return dropped;
}

int fill_small_holes(QuadMesh& q, int max_loop, const std::function<bool(const std::vector<int>&)>& allowed) {
  // Directed sides; a side a→b whose reverse is missing is a boundary half-edge (the face on its left).
  std::unordered_map<Key, int> directed;
  auto dkey = [](int a, int b) {
    return (static_cast<Key>(static_cast<unsigned>(a)) << 32) | static_cast<unsigned>(b);
  };
  for (const auto& F : q.faces)
    for (std::size_t i = 0; i < F.size(); ++i) ++directed[dkey(F[i], F[(i + 1) % F.size()])];
  // Components through shared edges: only holes of a component with at least a quarter of the faces are closed
  // (a small piece cut off by folds would otherwise become a closed blob).
  const int nf = q.num_faces();
  const FaceComponents components = face_components(q);
  std::unordered_map<int, std::vector<int>> next;  // boundary half-edges leaving a vertex
  std::vector<std::tuple<int, int, int>> starts;   // (a, b, face)
  for (int f = 0; f < nf; ++f) {
    const auto& F = q.faces[f];
    for (std::size_t i = 0; i < F.size(); ++i) {
      const int a = F[i], b = F[(i + 1) % F.size()];
      if (!directed.count(dkey(b, a))) next[a].push_back(b), starts.emplace_back(a, b, f);
    }
  }
  std::sort(starts.begin(), starts.end());  // deterministic order
  std::unordered_set<Key> used;
  int filled = 0;
  for (const auto& [a0, b0, f0] : starts) {
    if (used.count(dkey(a0, b0))) continue;
    const bool big = 4 * components.size[components.of_face[f0]] >= nf;
    std::vector<int> loop = {a0};
    bool ok = true;
    int a = a0, b = b0;
    while (b != a0) {
      used.insert(dkey(a, b));
      const auto it = next.find(b);
      if (it == next.end() || it->second.size() != 1 || static_cast<int>(loop.size()) >= max_loop) {
        ok = false;  // pinched boundary vertex or a long loop (a real boundary): leave it
        break;
      }
      loop.push_back(b);
      a = b;
      b = it->second[0];
    }
    used.insert(dkey(a, b));
    if (!ok || !big || loop.size() < 3) continue;
    std::vector<int> sorted = loop;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end() || !allowed(loop)) continue;
    std::reverse(loop.begin(), loop.end());
    q.faces.push_back(std::move(loop));
    ++filled;
  }
  return filled;
}

}  // namespace quadcover
