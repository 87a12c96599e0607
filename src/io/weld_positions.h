#pragma once
// Vertices at one point: bit-identical positions (−0 as +0) count as one point, as STL's corners are welded
// (io/read_stl.cpp) and as `remesh` welds the seams of a file whose surface is cut into pieces (cli/common.h).
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "io/polygon_soup.h"

namespace quadcover {

/// The bits of a position, −0 as +0: equal keys are the same point.
struct PositionKey {
  std::uint64_t x, y, z;
  bool operator==(const PositionKey&) const = default;
  /// \pre none
  static PositionKey of(const double p[3]) { return {bits(p[0]), bits(p[1]), bits(p[2])}; }

 private:
  static std::uint64_t bits(double d) { return std::bit_cast<std::uint64_t>(d == 0.0 ? 0.0 : d); }
};

struct PositionHash {
  /// \pre none
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h ^= (k.y + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2)) * 0xBF58476D1CE4E5B9ull;
    h ^= (k.z + 0x94D049BB133111EBull + (h << 6) + (h >> 2)) * 0x94D049BB133111EBull;
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

/// What weld_identical_positions did.
struct Welding {
  std::vector<std::int64_t> into;  ///< #V: the first vertex at each vertex's position (itself when it is the first)
  std::size_t merged = 0;          ///< vertices used by a face that were merged into an earlier one
};

/// Every face corner at a vertex whose position equals an earlier vertex's is moved to that earlier vertex (the
/// later one stays in `positions`, used by no face). Indices out of range are left as they are (validation reports
/// them). \pre none
Welding weld_identical_positions(PolygonSoup& soup);

}  // namespace quadcover
