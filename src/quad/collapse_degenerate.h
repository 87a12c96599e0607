#pragma once
// Collapse of mesh edges that the map sends to a single point (thesis 2.1 requirement 2 fails there: both triangles
// of the edge have zero parameter area whatever the other vertices do). Typically two branch points rounded onto
// the same integer point (4.2.2). Merging the two vertices removes the two degenerate triangles; the remaining
// triangles keep their corner coordinates, and the two triangles that met the removed one along its other edges
// are glued with the composed transition (i^{k2}(i^{k1} z + c1) + c2). The merged point is one output vertex, so
// extraction no longer has to cut a hole around it.
#include <vector>

#include "mesh/mesh.h"
#include "param/parameterization.h"

namespace quadcover {

struct CollapsedMap {
  Mesh mesh;                     ///< the mesh with the edges collapsed (empty if none was)
  Parameterization param;        ///< per-corner coordinates and per-edge transitions on `mesh`
  std::vector<int> face_origin;  ///< face of `mesh` -> face of the input mesh
  int collapsed_edges = 0;
};

/// Collapses interior edges whose endpoints' coordinates (in either adjacent chart) differ by at most `tol` grid
/// units and that are one point for the extraction: one of the edge's triangles is not grid::positive_in_map, or
/// both endpoints are within tol / 2 of one lattice point (the grid map snaps them together); and when the collapse
/// keeps the mesh manifold (link condition; edges with a boundary endpoint are kept).
/// Repeats while clusters remain (at most `max_passes` rebuilds). collapsed_edges == 0: nothing changed.
/// \pre param.uv is #F by 3 and the transitions are per edge (Parameterization's convention).
CollapsedMap collapse_zero_edges(const Mesh& mesh, const Parameterization& param, double tol, int max_passes = 4);

}  // namespace quadcover
