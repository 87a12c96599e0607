#include "mesh/edge_table.h"

#include <algorithm>

namespace quadcover {

EdgeTable::EdgeTable(std::size_t num_vertices, const std::vector<std::array<std::int64_t, 3>>& tris) {
  const std::size_t nh = 3 * tris.size();
  // Bucket half-edges by their smaller endpoint (counting sort), then order each bucket by the larger one.
  std::vector<std::size_t> bucket(num_vertices + 1, 0);
  auto ends = [&](std::size_t h) {
    const auto& c = tris[h / 3];
    const int k = static_cast<int>(h % 3);
    const std::int64_t a = c[(k + 1) % 3], b = c[(k + 2) % 3];
    return std::array<std::int64_t, 2>{a, b};
  };
  for (std::size_t h = 0; h < nh; ++h) {
    const auto [a, b] = ends(h);
    ++bucket[static_cast<std::size_t>(std::min(a, b)) + 1];
  }
  for (std::size_t v = 0; v < num_vertices; ++v) bucket[v + 1] += bucket[v];
  // Within a bucket, order half-edges by (larger endpoint, half-edge id): one packed 64-bit key each, so the
  // sort compares integers instead of recomputing endpoints.
  std::vector<std::uint64_t> sorted(nh);
  {
    std::vector<std::size_t> fill(bucket.begin(), bucket.end() - 1);
    for (std::size_t h = 0; h < nh; ++h) {
      const auto [a, b] = ends(h);
      sorted[fill[static_cast<std::size_t>(std::min(a, b))]++] =
          (static_cast<std::uint64_t>(std::max(a, b)) << 32) | static_cast<std::uint64_t>(h);
    }
  }
  halfedge_edge_.assign(nh, 0);
  incidences_.reserve(nh);
  begin_.reserve(nh / 2 + 2);
  endpoints_.reserve(nh / 2 + 2);
  for (std::size_t v = 0; v < num_vertices; ++v) {
    auto first = sorted.begin() + static_cast<std::ptrdiff_t>(bucket[v]);
    auto last = sorted.begin() + static_cast<std::ptrdiff_t>(bucket[v + 1]);
    std::sort(first, last);
    for (auto it = first; it != last;) {
      const std::uint64_t hi = *it >> 32;
      const auto id = static_cast<std::uint32_t>(endpoints_.size());
      endpoints_.push_back({static_cast<std::int64_t>(v), static_cast<std::int64_t>(hi)});
      begin_.push_back(incidences_.size());
      for (; it != last && (*it >> 32) == hi; ++it) {
        const auto h = static_cast<std::uint32_t>(*it & 0xffffffffu);
        const auto e = ends(h);
        halfedge_edge_[h] = id;
        incidences_.push_back({h / 3, static_cast<std::uint8_t>(h % 3), e[0] < e[1]});
      }
    }
  }
  begin_.push_back(incidences_.size());
}

}  // namespace quadcover

namespace quadcover {

OrientationResult orient_consistently(const EdgeTable& edges, std::size_t num_tris, const std::vector<char>& skip_edge) {
  OrientationResult result;
  std::vector<signed char> flip(num_tris, -1);
  std::vector<std::uint32_t> queue;
  result.flip.assign(num_tris, 0);
  for (std::size_t seed = 0; seed < num_tris; ++seed) {
    if (flip[seed] >= 0) continue;
    flip[seed] = 0;
    queue.assign(1, static_cast<std::uint32_t>(seed));
    std::size_t flipped = 0;
    for (std::size_t qi = 0; qi < queue.size(); ++qi) {
      const std::uint32_t t = queue[qi];
      flipped += static_cast<std::size_t>(flip[t]);
      for (int k = 0; k < 3; ++k) {
        const std::size_t e = edges.face_edge(t, k);
        const auto inc = edges.incidences(e);
        if (inc.size() != 2 || (!skip_edge.empty() && skip_edge[e])) continue;
        const auto& a = inc[0].tri == t ? inc[0] : inc[1];
        const auto& b = inc[0].tri == t ? inc[1] : inc[0];
        // After flipping, a and b must traverse e in opposite directions.
        const signed char want = static_cast<signed char>(((a.forward != (flip[t] != 0)) == b.forward) ? 1 : 0);
        if (flip[b.tri] < 0) {
          flip[b.tri] = want;
          queue.push_back(b.tri);
        } else if (flip[b.tri] != want && result.orientable) {
          result.orientable = false;
          result.witness = b.tri;
        }
      }
    }
    // Keep the majority orientation of the component.
    const bool invert = 2 * flipped > queue.size();
    for (std::uint32_t t : queue) result.flip[t] = static_cast<char>((flip[t] != 0) != invert);
    result.flips += invert ? queue.size() - flipped : flipped;
  }
  return result;
}

}  // namespace quadcover
