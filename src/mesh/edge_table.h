#pragma once
// Undirected edges of a triangle list with their face incidences, built in linear time by bucketing the
// half-edges on their smaller endpoint. Edges are numbered in lexicographic (min, max) order, so the numbering
// depends only on the input (deterministic). Shared by validation and Mesh connectivity.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace quadcover {

class EdgeTable {
 public:
  struct Incidence {
    std::uint32_t tri;  ///< triangle index in the list given to the constructor
    std::uint8_t k;     ///< face edge k (opposite corner k, from corner k+1 to corner k+2)
    bool forward;       ///< the triangle traverses the edge from its smaller to its larger endpoint
  };

  /// \pre every index in tris is in [0, num_vertices); fewer than 2^32 triangles.
  EdgeTable(std::size_t num_vertices, const std::vector<std::array<std::int64_t, 3>>& tris);

  std::size_t num_edges() const { return endpoints_.size(); }  ///< \pre none
  /// (smaller, larger) endpoint of edge e. \pre e < num_edges()
  const std::array<std::int64_t, 2>& endpoints(std::size_t e) const { return endpoints_[e]; }
  /// All triangles containing edge e (one for boundary, two for manifold interior, more if non-manifold).
  /// \pre e < num_edges()
  std::span<const Incidence> incidences(std::size_t e) const {
    return {incidences_.data() + begin_[e], incidences_.data() + begin_[e + 1]};
  }
  /// The edge of face edge k of triangle t. \pre t < #triangles, 0 <= k < 3
  std::size_t face_edge(std::size_t t, int k) const { return halfedge_edge_[3 * t + static_cast<std::size_t>(k)]; }

 private:
  std::vector<std::array<std::int64_t, 2>> endpoints_;
  std::vector<Incidence> incidences_;
  std::vector<std::size_t> begin_;
  std::vector<std::uint32_t> halfedge_edge_;
};

}  // namespace quadcover

namespace quadcover {

/// A consistent orientation of the triangles, found by breadth-first propagation across manifold edges
/// (edges with exactly two incidences and not marked in `skip_edge`).
struct OrientationResult {
  bool orientable = true;
  std::uint32_t witness = 0;   ///< a triangle where propagation met a contradiction (when not orientable)
  std::vector<char> flip;      ///< per triangle: reverse it; per component the smaller set is flipped
  std::size_t flips = 0;
};
/// \pre edges was built from the same num_tris triangles; skip_edge has edges.num_edges() entries.
OrientationResult orient_consistently(const EdgeTable& edges, std::size_t num_tris, const std::vector<char>& skip_edge);

}  // namespace quadcover
