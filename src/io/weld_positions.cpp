#include "io/weld_positions.h"

#include <unordered_map>
#include <vector>

namespace quadcover {

Welding weld_identical_positions(PolygonSoup& soup) {
  const auto n = static_cast<std::int64_t>(soup.num_vertices());
  std::unordered_map<PositionKey, std::int64_t, PositionHash> first;
  first.reserve(static_cast<std::size_t>(n));
  Welding w;
  std::vector<std::int64_t>& into = w.into;
  into.resize(static_cast<std::size_t>(n));
  for (std::int64_t v = 0; v < n; ++v) {
    const double p[3] = {soup.positions(v, 0), soup.positions(v, 1), soup.positions(v, 2)};
    into[static_cast<std::size_t>(v)] = first.try_emplace(PositionKey::of(p), v).first->second;
  }
  std::vector<char> merged(static_cast<std::size_t>(n), 0);
  for (std::int64_t& c : soup.face_vertices) {
    if (c < 0 || c >= n || into[static_cast<std::size_t>(c)] == c) continue;
    merged[static_cast<std::size_t>(c)] = 1;
    c = into[static_cast<std::size_t>(c)];
  }
  for (char m : merged) w.merged += static_cast<std::size_t>(m);
  return w;
}

}  // namespace quadcover
