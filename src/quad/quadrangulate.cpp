#include "quad/quadrangulate.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iterator>
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

// Removes the faces flagged in `removed` (one flag per face), keeping the others in order, then appends `added`.
void replace_faces(QuadMesh& q, const std::vector<char>& removed, std::vector<std::vector<int>> added) {
  std::vector<std::vector<int>> faces;
  faces.reserve(q.faces.size() + added.size());
  for (std::size_t f = 0; f < q.faces.size(); ++f)
    if (!removed[f]) faces.push_back(std::move(q.faces[f]));
  for (auto& F : added) faces.push_back(std::move(F));
  q.faces = std::move(faces);
}

// Renames corner `from` of face F to `to` and removes the repeat this leaves where they were neighbours.
void rename_corner(std::vector<int>& F, int from, int to) {
  std::replace(F.begin(), F.end(), from, to);
  F.erase(std::unique(F.begin(), F.end()), F.end());
  if (F.size() > 1 && F.front() == F.back()) F.pop_back();
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
  PolygonQuadrangulation(QuadMesh& q, int max_size, bool with_boundary)
      : q_(q), max_size_(max_size), nf_(q.num_faces()), with_boundary_(with_boundary) {
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
      if (n == 4 || n % 2 || n > max_size_ || !allowed(f)) continue;
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
    if (!added_.empty()) replace_faces(q_, consumed_, std::move(added_));
    return rep_;
  }

 private:
  // Every side of f has two faces, or f may have sides on the boundary (with_boundary_).
  bool allowed(int f) {
    if (with_boundary_) return true;
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
           allowed(g);
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
  const bool with_boundary_;
  std::unordered_map<Key, int> uses_;
  std::unordered_map<Key, std::pair<int, int>> faces_of_;  // undirected edge -> (first face, second face)
  std::vector<char> consumed_;
  std::vector<std::vector<int>> added_;
  Splitter splitter_{q_.V, uses_};
  QuadrangulateReport rep_;
};

}  // namespace

QuadrangulateReport quadrangulate_polygons(QuadMesh& q, int max_size, bool with_boundary) {
  if (q.num_quads() == q.num_faces()) return {};
  PolygonQuadrangulation interior(q, max_size, false);
  interior.split_even();
  interior.merge_odd();
  QuadrangulateReport rep = interior.finish();
  if (!with_boundary || q.num_quads() == q.num_faces()) return rep;
  PolygonQuadrangulation boundary(q, max_size, true);
  boundary.split_even();
  boundary.merge_odd();
  const QuadrangulateReport b = boundary.finish();
  rep.boundary_split_polygons = b.split_polygons;
  rep.boundary_merged_pairs = b.merged_pairs;
  return rep;
}

namespace {

/// Per vertex: the faces around it and its neighbours along face sides (sorted).
struct PolygonStar {
  std::vector<std::vector<int>> faces, neighbours;
  explicit PolygonStar(const QuadMesh& q)
      : faces(static_cast<std::size_t>(q.num_vertices())), neighbours(static_cast<std::size_t>(q.num_vertices())) {
    for (int f = 0; f < q.num_faces(); ++f) {
      const auto& F = q.faces[f];
      for (std::size_t i = 0; i < F.size(); ++i) {
        faces[F[i]].push_back(f);
        neighbours[F[i]].push_back(F[(i + 1) % F.size()]);
        neighbours[F[(i + 1) % F.size()]].push_back(F[i]);
      }
    }
    for (auto& n : neighbours) {
      std::sort(n.begin(), n.end());
      n.erase(std::unique(n.begin(), n.end()), n.end());
    }
  }
  // The vertices next to both a and b.
  std::vector<int> common(int a, int b) const {
    std::vector<int> out;
    std::set_intersection(neighbours[a].begin(), neighbours[a].end(), neighbours[b].begin(), neighbours[b].end(),
                          std::back_inserter(out));
    return out;
  }
};

// Whether quad F, with vertex `from` renamed `to` and `to` placed at `at`, is not folded over: its Newell normal
// keeps its side and at most one corner turns against it (a reflex corner, which smoothing can straighten; two make
// a bow-tie). Faces that are not quads after the renaming pass.
bool unfolded_after(const QuadMesh& q, const std::vector<int>& F, int from, int to, const Eigen::Vector3d& at) {
  std::vector<int> G = F;
  rename_corner(G, from, to);
  if (G.size() != 4) return true;
  const auto before = [&](int v) { return Eigen::Vector3d(q.V.row(v).transpose()); };
  const auto after = [&](int v) { return v == to ? at : before(v); };
  Eigen::Vector3d n0 = Eigen::Vector3d::Zero(), n1 = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < F.size(); ++i) n0 += before(F[i]).cross(before(F[(i + 1) % F.size()]));
  for (int i = 0; i < 4; ++i) n1 += after(G[i]).cross(after(G[(i + 1) % 4]));
  int against = 0;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d a = after(G[(i + 3) % 4]), b = after(G[i]), c = after(G[(i + 1) % 4]);
    against += (b - a).cross(c - b).dot(n0) <= 0;
  }
  return n1.dot(n0) > 0 && against <= 1;
}

}  // namespace

int collapse_boundary_triangles(QuadMesh& q) {
  const std::vector<char> on_boundary = quad_boundary_vertices(q);
  const PolygonStar star(q);
  std::unordered_map<Key, std::vector<int>> faces_of;
  for (int f = 0; f < q.num_faces(); ++f)
    for (std::size_t i = 0; i < q.faces[f].size(); ++i)
      faces_of[edge_key(q.faces[f][i], q.faces[f][(i + 1) % q.faces[f].size()])].push_back(f);
  std::vector<char> touched(static_cast<std::size_t>(q.num_vertices()), 0), removed(q.faces.size(), 0);
  int collapsed = 0;
  for (int t = 0; t < q.num_faces(); ++t) {
    const auto& T = q.faces[t];
    if (T.size() != 3 || removed[t]) continue;
    for (int k = 0; k < 6; ++k) {  // g = T[i] and c either of the other two corners
      const int i = k / 2, g = T[i], c = T[(i + 1 + k % 2) % 3], x = T[(i + 2 - k % 2) % 3];
      const auto& across = faces_of[edge_key(g, c)];
      if (on_boundary[g] || !on_boundary[c] || !on_boundary[x] || faces_of[edge_key(c, x)].size() != 1 ||
          across.size() != 2)
        continue;
      const int p = across[0] == t ? across[1] : across[0];
      const bool odd = q.faces[p].size() % 2 == 1 && q.faces[p].size() >= 5;
      if (!odd || removed[p] || star.common(g, c) != std::vector<int>{x}) continue;
      bool free = true;  // nothing around g touched yet, and no face but T and P holds both g and c
      for (int f : star.faces[g])
        for (int v : q.faces[f]) free = free && !touched[v] && (v != c || f == t || f == p);
      for (int f : star.faces[g]) free = free && (f == t || unfolded_after(q, q.faces[f], g, c, q.V.row(c)));
      if (!free) continue;
      for (int f : star.faces[g])
        for (int v : q.faces[f]) touched[v] = 1;
      for (int f : star.faces[g])
        if (f != t) rename_corner(q.faces[f], g, c);  // P loses a corner, the others take c for g
      removed[t] = 1;
      ++collapsed;
      break;
    }
  }
  replace_faces(q, removed, {});
  return collapsed;
}

namespace {

// The state of split_odd_boundary_polygons: the edges' uses and faces, the faces consumed and the quads added.
class OddBoundarySplit {
 public:
  OddBoundarySplit(QuadMesh& q, const BoundaryMidpoint& midpoint) : q_(q), midpoint_(midpoint) {
    for (int f = 0; f < q.num_faces(); ++f)
      for (std::size_t i = 0; i < q.faces[f].size(); ++i) {
        const Key k = edge_key(q.faces[f][i], q.faces[f][(i + 1) % q.faces[f].size()]);
        ++uses_[k];
        faces_of_[k].push_back(f);
      }
    consumed_.assign(q.faces.size(), 0);
  }

  // f alone, else merged with each quad beside it: the first loop that splits.
  bool try_face(int f, int max_size) {
    const auto& F = q_.faces[f];
    if (consumed_[f] || F.size() % 2 == 0 || static_cast<int>(F.size()) > max_size) return false;
    // A triangle alone becomes a quad with its new corner on the boundary: worth it only where the boundary turns
    // between its two boundary sides (a corner cut off), else that corner is flat.
    if ((F.size() >= 5 || boundary_sides(F) >= 2) && try_loop(F, {f}, {}, F.size() == 3)) return true;
    for (std::size_t i = 0; i < F.size(); ++i) {
      const Key k = edge_key(F[i], F[(i + 1) % F.size()]);
      const auto& two = faces_of_[k];
      if (two.size() != 2) continue;
      const int g = two[0] == f ? two[1] : two[0];
      std::vector<int> merged;
      Key removed = 0;
      if (consumed_[g] || q_.faces[g].size() != 4 || !merge_loops(F, q_.faces[g], merged, removed)) continue;
      if (try_loop(merged, {f, g}, {removed})) return true;
      if (F.size() == 3 && try_second_quad(f, g, merged, removed)) return true;
    }
    return false;
  }

  // A triangle f merged with quad g (`merged`), then with the quad across another side of f.
  bool try_second_quad(int f, int g, const std::vector<int>& merged, Key removed) {
    const auto& F = q_.faces[f];
    for (std::size_t i = 0; i < F.size(); ++i) {
      const auto& two = faces_of_[edge_key(F[i], F[(i + 1) % F.size()])];
      if (two.size() != 2) continue;
      const int h = two[0] == f ? two[1] : two[0];
      std::vector<int> both;
      Key second = 0;
      if (h == g || consumed_[h] || q_.faces[h].size() != 4 || !merge_loops(merged, q_.faces[h], both, second))
        continue;
      if (try_loop(both, {f, g, h}, {removed, second})) return true;
    }
    return false;
  }

  int finish() {
    if (!added_.empty()) replace_faces(q_, consumed_, std::move(added_));
    return made_;
  }

 private:
  int boundary_sides(const std::vector<int>& F) {
    int n = 0;
    for (std::size_t i = 0; i < F.size(); ++i) n += uses_[edge_key(F[i], F[(i + 1) % F.size()])] == 1;
    return n;
  }
  // The largest corner angle of quad Q (radians).
  double largest_corner(const std::vector<int>& Q) const {
    double largest = 0;
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d u = q_.V.row(Q[(i + 3) % 4]) - q_.V.row(Q[i]),
                            w = q_.V.row(Q[(i + 1) % 4]) - q_.V.row(Q[i]);
      largest = std::max(largest, std::atan2(u.cross(w).norm(), u.dot(w)));
    }
    return largest;
  }
  // The loop made even by a boundary vertex on one of its boundary sides (the longest first), then split; with
  // `no_flat_corner` (a triangle alone) not where its quad would have a corner over 160°.
  bool try_loop(const std::vector<int>& loop, const std::vector<int>& from, const std::vector<Key>& removed,
                bool no_flat_corner = false) {
    constexpr double kFlat = 160 * std::numbers::pi / 180;
    const int n = static_cast<int>(loop.size());
    std::vector<std::pair<double, int>> sides;  // (−length, index) of the boundary sides
    for (int i = 0; i < n; ++i)
      if (uses_[edge_key(loop[i], loop[(i + 1) % n])] == 1)
        sides.emplace_back(-(q_.V.row(loop[i]) - q_.V.row(loop[(i + 1) % n])).norm(), i);
    std::sort(sides.begin(), sides.end());
    for (const auto& [minus_length, side] : sides) {
      const int a = loop[side], b = loop[(side + 1) % n];
      const std::optional<BoundaryPoint> mid = midpoint_(q_.V.row(a).transpose(), q_.V.row(b).transpose());
      if (!mid) continue;
      const int m = add_vertex(*mid);
      std::vector<int> even(loop.begin(), loop.begin() + side + 1);
      even.push_back(m);
      even.insert(even.end(), loop.begin() + side + 1, loop.end());
      std::vector<std::vector<int>> quads;
      if (!splitter_.split(even, quads) || (no_flat_corner && largest_corner(quads[0]) > kFlat)) {
        remove_last_vertex();
        continue;
      }
      uses_.erase(edge_key(a, b));
      for (Key k : removed) uses_.erase(k);
      uses_[edge_key(a, m)] = uses_[edge_key(m, b)] = 1;
      for (const auto& Q : quads)
        for (int i = 0; i < 4; ++i) uses_.try_emplace(edge_key(Q[i], Q[(i + 1) % 4]), 2);
      for (int g : from) consumed_[g] = 1;
      added_.insert(added_.end(), quads.begin(), quads.end());
      ++made_;
      return true;
    }
    return false;
  }
  int add_vertex(const BoundaryPoint& p) {
    const int m = q_.num_vertices();
    q_.V.conservativeResize(m + 1, Eigen::NoChange);
    q_.V.row(m) = p.position.transpose();
    q_.uv.conservativeResize(m + 1);
    q_.uv[m] = p.uv;
    q_.source_face.conservativeResize(m + 1);
    q_.source_face[m] = p.face;
    q_.on_grid.conservativeResize(m + 1);
    q_.on_grid[m] = 0;
    return m;
  }
  void remove_last_vertex() {
    const int m = q_.num_vertices() - 1;
    q_.V.conservativeResize(m, Eigen::NoChange);
    q_.uv.conservativeResize(m);
    q_.source_face.conservativeResize(m);
    q_.on_grid.conservativeResize(m);
  }

  QuadMesh& q_;
  const BoundaryMidpoint& midpoint_;
  std::unordered_map<Key, int> uses_;
  std::unordered_map<Key, std::vector<int>> faces_of_;
  std::vector<char> consumed_;
  std::vector<std::vector<int>> added_;
  Splitter splitter_{q_.V, uses_};
  int made_ = 0;
};

}  // namespace

int split_odd_boundary_polygons(QuadMesh& q, const BoundaryMidpoint& midpoint, int max_size) {
  if (q.num_quads() == q.num_faces()) return 0;
  OddBoundarySplit run(q, midpoint);
  for (int f = 0; f < q.num_faces(); ++f) run.try_face(f, max_size);
  return run.finish();
}

int collapse_boundary_sides(QuadMesh& q, const BoundaryMidpoint& midpoint) {
  const std::vector<char> on_boundary = quad_boundary_vertices(q);
  const PolygonStar star(q);
  std::vector<char> touched(static_cast<std::size_t>(q.num_vertices()), 0), removed(q.faces.size(), 0);
  int collapsed = 0;
  for (int t = 0; t < q.num_faces(); ++t) {
    const auto& T = q.faces[t];
    if (T.size() != 3) continue;
    for (int i = 0; i < 3; ++i) {
      const int g = T[i], c = T[(i + 1) % 3], x = T[(i + 2) % 3];
      if (on_boundary[g] || !on_boundary[c] || !on_boundary[x] || star.common(c, x) != std::vector<int>{g}) continue;
      bool free = true;
      for (int v : {c, x})
        for (int f : star.faces[v])
          for (int w : q.faces[f]) free = free && !touched[w] && (v != x || w != c || f == t);  // only T has both
      if (!free) continue;
      const std::optional<BoundaryPoint> mid = midpoint(q.V.row(c).transpose(), q.V.row(x).transpose());
      if (!mid) continue;
      for (int v : {c, x})
        for (int f : star.faces[v]) free = free && (f == t || unfolded_after(q, q.faces[f], x, c, mid->position));
      if (!free) continue;
      for (int v : {c, x})
        for (int f : star.faces[v])
          for (int w : q.faces[f]) touched[w] = 1;
      for (int f : star.faces[x])
        if (f != t) rename_corner(q.faces[f], x, c);
      q.V.row(c) = mid->position.transpose();
      q.uv[c] = mid->uv;
      q.source_face[c] = mid->face;
      q.on_grid[c] = 0;
      removed[t] = 1;
      ++collapsed;
      break;
    }
  }
  replace_faces(q, removed, {});
  return collapsed;
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
