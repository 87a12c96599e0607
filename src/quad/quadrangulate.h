#pragma once
// Turning the polygons that extraction leaves (around cut-out folds, off-grid branch points) into quads where the
// mesh allows it (issue 7: all-quad output): an interior polygon with an even number of corners is split into
// quads by diagonals between its corners; two adjacent interior polygons with an odd number of corners are first
// merged across their shared edge. A split is taken only if every new quad is convex on the surface (corners turn
// the same way as the polygon's Newell normal) and no diagonal duplicates an existing edge, so the mesh stays a
// manifold with the same Euler characteristic (each diagonal adds one edge and one face; a merge removes one of
// each). Among the valid splits the one closest to right angles in 3D is chosen.
#include <functional>
#include <vector>

#include "quad/quad_mesh.h"

namespace quadcover {

struct QuadrangulateReport {
  int split_polygons = 0;   ///< even polygons split into quads
  int merged_pairs = 0;     ///< pairs of odd polygons merged (then split, or already a quad)
};

/// Works on faces with at most `max_size` corners (default 8) whose edges all have a face on either side.
/// \pre q is an oriented polygon mesh (every face index < q.num_vertices()). \throw only std::bad_alloc.
QuadrangulateReport quadrangulate_polygons(QuadMesh& q, int max_size = 8);

/// Removes connected components that are closed but have fewer than `min_faces` faces: pieces such as two quads
/// glued along all their sides, which extraction can leave inside a cut-out fold (a closed quad surface needs at
/// least 6 faces). Returns the number of faces removed. \pre as quadrangulate_polygons. \throw only std::bad_alloc.
int drop_closed_debris(QuadMesh& q, int min_faces = 6);

/// Closes each hole whose boundary loop is simple, has 3..max_loop edges, lies on a component holding at least a
/// quarter of the faces and passes `allowed` (given the loop's vertices) with one polygon face (the loop reversed). Meant for the small holes left where folded triangles were
/// cut out: the face covers the disk the fold occupied, so χ rises by one per hole and the boundary loops drop by
/// one (the capped surface is unchanged). Returns the number of holes filled.
/// \pre as quadrangulate_polygons; max_loop >= 3 to fill anything. Throws only what `allowed` throws.
int fill_small_holes(QuadMesh& q, int max_loop, const std::function<bool(const std::vector<int>&)>& allowed);

}  // namespace quadcover
