#pragma once
// Turning the polygons that extraction leaves (around cut-out folds, off-grid branch points) into quads where the
// mesh allows it (issue 7: all-quad output): an interior polygon with an even number of corners is split into
// quads by diagonals between its corners; two adjacent interior polygons with an odd number of corners are first
// merged across their shared edge. A split is taken only if every new quad is convex on the surface (corners turn
// the same way as the polygon's Newell normal) and no diagonal duplicates an existing edge, so the mesh stays a
// manifold with the same Euler characteristic (each diagonal adds one edge and one face; a merge removes one of
// each). Among the valid splits the one closest to right angles in 3D is chosen.
#include "quad/quad_mesh.h"

namespace quadcover {

struct QuadrangulateReport {
  int split_polygons = 0;   ///< even polygons split into quads
  int merged_pairs = 0;     ///< pairs of odd polygons merged (then split, or already a quad)
};

/// Works on faces with at most `max_size` corners (default 8) whose edges all have a face on either side.
QuadrangulateReport quadrangulate_polygons(QuadMesh& q, int max_size = 8);

}  // namespace quadcover
