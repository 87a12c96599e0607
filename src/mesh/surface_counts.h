#pragma once
// The topology of a polygon mesh counted from its faces alone: the one definition of manifold, oriented, boundary
// loops, components, genus and non-quads that `info`, `metrics`, every report and the tests use (issue 18 item 7).
// Manifoldness does not depend on orientation (a Klein bottle is a manifold that cannot be oriented); whether the
// faces agree in orientation is counted separately.
#include <nlohmann/json.hpp>
#include <vector>

#include "io/polygon_soup.h"

namespace quadcover {

class Mesh;

struct SurfaceCounts {
  int vertices = 0;           ///< vertices some face uses
  int isolated_vertices = 0;  ///< vertices no face uses (not in χ)
  int edges = 0;              ///< distinct unordered pairs of consecutive corners
  int faces = 0;
  int boundary_edges = 0;         ///< edges of one face side
  int non_manifold_edges = 0;     ///< edges of more than two face sides
  int inconsistent_edges = 0;     ///< edges of two face sides running the same way (neighbours disagree in orientation)
  int non_manifold_vertices = 0;  ///< vertices whose corners form more than one fan (linked through two-sided edges)
  int degenerate_faces = 0;       ///< faces with fewer than 3 corners or a repeated corner
  int components = 0;             ///< connected through shared vertices
  int boundary_loops = 0;         ///< cycles of boundary edges, each followed inside one fan at every vertex
  int euler_characteristic = 0;   ///< χ = vertices − edges + faces (1.1)
  /// Σ over components of g from χ = 2 − 2g − b (1.2) = (2·components − χ − boundary_loops) / 2; −1 (undefined)
  /// unless the mesh is manifold and oriented.
  int genus = -1;
  int non_quads = 0;  ///< faces with other than four corners
  /// \pre none
  bool manifold() const { return non_manifold_edges == 0 && non_manifold_vertices == 0 && degenerate_faces == 0; }
  bool oriented() const { return inconsistent_edges == 0; }  ///< \pre none
  bool closed() const { return boundary_edges == 0; }  ///< \pre none
};

/// Counts of a polygon mesh (faces of any size) over `num_vertices` vertices. O(n log n) in the corners,
/// deterministic. \pre every index is in [0, num_vertices).
SurfaceCounts surface_counts(int num_vertices, const std::vector<std::vector<int>>& faces);
/// Counts of a triangle mesh, by the same code (a valid Mesh gives its own num_components(), num_boundary_loops(),
/// genus()). \pre none
SurfaceCounts surface_counts(const Mesh& mesh);

/// The faces of a soup as read (polygons of any size, 0-based indices).
/// \throw InputError naming the file and line of the first face with a vertex index out of range.
std::vector<std::vector<int>> soup_polygons(const PolygonSoup& soup);

/// The counts as `info`, `metrics` and the reports write them (genus null where undefined). \pre none
nlohmann::json to_json(const SurfaceCounts& counts);

}  // namespace quadcover
