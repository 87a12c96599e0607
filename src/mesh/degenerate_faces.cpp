#include "mesh/degenerate_faces.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <iterator>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

namespace quadcover {

namespace {

using Key = std::pair<std::int64_t, std::int64_t>;
Key edge_key(std::int64_t a, std::int64_t b) { return a < b ? Key{a, b} : Key{b, a}; }
struct KeyHash {
  std::size_t operator()(const Key& k) const { return std::hash<std::int64_t>()(k.first * 1000003 + k.second); }
};

// The soup's faces as a working list.
struct FaceList {
  const PolygonSoup& soup;
  double tolerance;
  std::vector<std::vector<std::int64_t>> corners;
  std::vector<char> removed;

  bool triangle(std::size_t f) const {
    if (removed[f] || corners[f].size() != 3) return false;
    for (std::int64_t v : corners[f])
      if (v < 0 || v >= static_cast<std::int64_t>(soup.num_vertices())) return false;
    return true;
  }
  Eigen::Vector3d at(std::int64_t v) const { return soup.positions.row(v).transpose(); }
  bool zero_area(std::int64_t a, std::int64_t b, std::int64_t c) const {
    const Eigen::Vector3d p = at(a), q = at(b), r = at(c);
    const double longest2 = std::max({(q - p).squaredNorm(), (r - q).squaredNorm(), (p - r).squaredNorm()});
    return !((q - p).cross(r - p).norm() > tolerance * longest2);
  }
  // The corner of triangle f strictly inside its opposite edge (a cap), or -1 (a needle, or not collinear).
  int cap_corner(std::size_t f) const {
    const auto& t = corners[f];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d m = at(t[k]), a = at(t[(k + 1) % 3]), b = at(t[(k + 2) % 3]);
      const double length2 = (b - a).squaredNorm(), s = (m - a).dot(b - a) / length2;
      if (length2 > 0 && s > 1e-9 && s < 1 - 1e-9) return k;
    }
    return -1;
  }
  std::unordered_map<Key, std::vector<std::size_t>, KeyHash> edge_faces() const {
    std::unordered_map<Key, std::vector<std::size_t>, KeyHash> out;
    for (std::size_t f = 0; f < corners.size(); ++f)
      if (triangle(f))
        for (int k = 0; k < 3; ++k) out[edge_key(corners[f][k], corners[f][(k + 1) % 3])].push_back(f);
    return out;
  }
};

void drop_repeats_and_duplicates(FaceList& list, DegenerateFaceRemoval& out) {
  std::vector<std::pair<std::array<std::int64_t, 3>, std::size_t>> keys;
  for (std::size_t f = 0; f < list.corners.size(); ++f) {
    if (!list.triangle(f)) continue;
    std::array<std::int64_t, 3> k{list.corners[f][0], list.corners[f][1], list.corners[f][2]};
    std::sort(k.begin(), k.end());
    if (k[0] == k[1] || k[1] == k[2]) {
      list.removed[f] = 1;
      ++out.repeated_vertex;
    } else {
      keys.emplace_back(k, f);
    }
  }
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 1; i < keys.size(); ++i)
    if (keys[i].first == keys[i - 1].first) list.removed[keys[i].second] = 1, ++out.duplicates;
}

// One pass over the caps; each face takes part in one change. \return whether anything changed.
bool remove_caps(FaceList& list, DegenerateFaceRemoval& out) {
  auto edges = list.edge_faces();
  std::vector<char> used(list.corners.size(), 0);
  std::set<Key> added;
  bool changed = false;
  for (std::size_t t = 0; t < list.corners.size(); ++t) {
    if (used[t] || !list.triangle(t)) continue;
    const auto& T = list.corners[t];
    if (!list.zero_area(T[0], T[1], T[2])) continue;
    const int k = list.cap_corner(t);
    if (k < 0) continue;
    const std::int64_t m = T[k], a = T[(k + 1) % 3], b = T[(k + 2) % 3];  // T = (m, a, b): the long edge a→b
    const auto& on_edge = edges[edge_key(a, b)];
    if (on_edge.size() == 1) {  // on the boundary: the boundary runs a → m → b instead
      list.removed[t] = used[t] = 1;
      ++out.boundary_caps;
      changed = true;
      continue;
    }
    if (on_edge.size() != 2) continue;
    const std::size_t nf = on_edge[0] == t ? on_edge[1] : on_edge[0];
    if (used[nf] || !list.triangle(nf)) continue;
    std::int64_t n = -1;
    for (std::int64_t v : list.corners[nf]) n = v != a && v != b ? v : n;
    if (n < 0 || n == m || edges.count(edge_key(m, n)) || added.count(edge_key(m, n))) continue;
    if (list.zero_area(a, n, m) || list.zero_area(n, b, m)) continue;
    list.corners[t] = {a, n, m};
    list.corners[nf] = {n, b, m};
    used[t] = used[nf] = 1;
    added.insert(edge_key(m, n));
    ++out.flipped_caps;
    changed = true;
  }
  return changed;
}

// The two corners of zero-area triangle f closest together (a needle's), as (a, b).
std::pair<std::int64_t, std::int64_t> shortest_edge(const FaceList& list, std::size_t f) {
  const auto& t = list.corners[f];
  int best = 0;
  for (int k = 1; k < 3; ++k)
    if ((list.at(t[k]) - list.at(t[(k + 1) % 3])).squaredNorm() <
        (list.at(t[best]) - list.at(t[(best + 1) % 3])).squaredNorm())
      best = k;
  return {t[best], t[(best + 1) % 3]};
}

// One pass over the needles (zero-area triangles that are not caps); each vertex takes part in one merge.
// \return whether anything changed.
bool merge_needles(FaceList& list, DegenerateFaceRemoval& out) {
  const auto edges = list.edge_faces();
  std::unordered_map<std::int64_t, std::vector<std::size_t>> faces_at;
  std::unordered_map<std::int64_t, std::set<std::int64_t>> neighbours;
  std::set<std::int64_t> on_boundary;
  for (const auto& [e, faces] : edges) {
    neighbours[e.first].insert(e.second), neighbours[e.second].insert(e.first);
    if (faces.size() == 1) on_boundary.insert(e.first), on_boundary.insert(e.second);
  }
  for (std::size_t f = 0; f < list.corners.size(); ++f)
    if (list.triangle(f))
      for (std::int64_t v : list.corners[f]) faces_at[v].push_back(f);
  std::set<std::int64_t> touched;
  bool changed = false;
  for (std::size_t t = 0; t < list.corners.size(); ++t) {
    if (!list.triangle(t)) continue;
    const auto& T = list.corners[t];
    if (!list.zero_area(T[0], T[1], T[2]) || list.cap_corner(t) >= 0) continue;
    const auto [a, b] = shortest_edge(list, t);
    if (touched.count(a) || touched.count(b)) continue;
    const auto& on_ab = edges.at(edge_key(a, b));
    std::set<std::int64_t> thirds, common;
    for (std::size_t f : on_ab)
      for (std::int64_t v : list.corners[f]) thirds.insert(v);
    thirds.erase(a), thirds.erase(b);
    std::set_intersection(neighbours[a].begin(), neighbours[a].end(), neighbours[b].begin(), neighbours[b].end(),
                          std::inserter(common, common.end()));
    const bool pinch = on_boundary.count(a) && on_boundary.count(b) && on_ab.size() != 1;
    if (common != thirds || pinch) continue;
    for (std::int64_t v : {a, b})
      for (std::size_t f : faces_at[v])
        for (std::int64_t w : list.corners[f]) touched.insert(w);
    for (std::size_t f : faces_at[b]) {
      auto& F = list.corners[f];
      if (std::find(F.begin(), F.end(), a) != F.end())
        list.removed[f] = 1;
      else
        std::replace(F.begin(), F.end(), b, a);
    }
    ++out.merged_needles;
    changed = true;
  }
  return changed;
}

}  // namespace

DegenerateFaceRemoval remove_degenerate_faces(PolygonSoup& soup, double tolerance) {
  constexpr int kPasses = 5;  // a flip can leave a neighbouring cap that the next pass takes
  DegenerateFaceRemoval out;
  FaceList list{soup, tolerance, {}, std::vector<char>(soup.num_faces(), 0)};
  for (std::size_t f = 0; f < soup.num_faces(); ++f)
    list.corners.emplace_back(soup.face_begin(f), soup.face_begin(f) + soup.face_size(f));
  drop_repeats_and_duplicates(list, out);
  for (int pass = 0; pass < kPasses; ++pass) {
    const bool caps = remove_caps(list, out);
    if (!merge_needles(list, out) && !caps) break;
  }
  if (out.total() == 0) return out;
  PolygonSoup kept = soup;
  kept.face_offsets = {0};
  kept.face_vertices.clear();
  kept.face_lines.clear();
  kept.face_uv.clear();
  for (std::size_t f = 0; f < list.corners.size(); ++f)
    if (!list.removed[f])
      kept.add_face(list.corners[f].data(), list.corners[f].size(), soup.face_lines.empty() ? 0 : soup.face_lines[f]);
  if (soup.face_lines.empty()) kept.face_lines.clear();
  soup = std::move(kept);
  return out;
}

}  // namespace quadcover
