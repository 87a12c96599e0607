#pragma once
// Turning the polygons that extraction leaves (around cut-out folds, off-grid branch points) into quads where the
// mesh allows it (issue 7: all-quad output): an interior polygon with an even number of corners is split into
// quads by diagonals between its corners; two adjacent interior polygons with an odd number of corners are first
// merged across their shared edge. A split is taken only if every new quad is convex on the surface (corners turn
// the same way as the polygon's Newell normal) and no diagonal duplicates an existing edge, so the mesh stays a
// manifold with the same Euler characteristic (each diagonal adds one edge and one face; a merge removes one of
// each). Among the valid splits the one closest to right angles in 3D is chosen.
#include <Eigen/Core>
#include <complex>
#include <functional>
#include <optional>
#include <vector>

#include "quad/quad_mesh.h"

namespace quadcover {

struct QuadrangulateReport {
  int split_polygons = 0;   ///< even polygons split into quads
  int merged_pairs = 0;     ///< pairs of odd polygons merged (then split, or already a quad)
  int boundary_split_polygons = 0;  ///< of the second pass, with sides on the boundary
  int boundary_merged_pairs = 0;    ///< of the second pass
};

/// Works on faces with at most `max_size` corners (default 8) whose edges all have a face on either side; then,
/// `with_boundary`, once more on the faces left, now also those with sides on the boundary (the clipped polygons
/// where iso-lines meet the boundary: a triangle and a pentagon cut from one grid cell merge into a hexagon).
/// \pre q is an oriented polygon mesh (every face index < q.num_vertices()). \throw only std::bad_alloc.
QuadrangulateReport quadrangulate_polygons(QuadMesh& q, int max_size = 8, bool with_boundary = false);

/// Where an iso-line meets the boundary at a shallow angle, it cuts a triangle T = (g, c, x) off the cell beside it:
/// a grid vertex g inside the mesh and two boundary points c, x, with the odd polygon P (five corners or more) across
/// the iso-line's last edge g–c. Collapsing that edge onto c (g moves onto the boundary) removes T and one corner
/// of P: with a pentagon, both become one quad. Done where g and c have no common neighbour but x and no common
/// face but T and P (the mesh stays a manifold with the same Euler characteristic: one vertex, two edges and one
/// face fewer), at most once around each vertex per call. g's other faces take c in its place; g is left unused.
/// Returns the number of triangles removed. \pre as quadrangulate_polygons. \throw only std::bad_alloc.
int collapse_boundary_triangles(QuadMesh& q);

/// A point on the input's boundary: where it is, the input triangle it lies on and φ there in that triangle's chart.
struct BoundaryPoint {
  Eigen::Vector3d position;
  int face = -1;
  std::complex<double> uv;
};
/// The point of the input's boundary halfway between the quad mesh's boundary points a and b (the ends of one side),
/// or nothing where the boundary between them is not found near the side.
using BoundaryMidpoint =
    std::function<std::optional<BoundaryPoint>(const Eigen::Vector3d& a, const Eigen::Vector3d& b)>;

/// An odd polygon with a side on the boundary and no odd partner (a pentagon where an iso-line meets the boundary
/// alone): a vertex on the boundary halfway along its longest boundary side (`midpoint`) makes it even, and it is
/// split into quads as above; a triangle is first merged with a quad beside it. Taken only where every new quad is
/// convex, so the mesh stays a manifold with the same Euler characteristic (one vertex, two edges and one face
/// more per split hexagon). Added vertices have on_grid 0. Returns the number of polygons made quads this way.
/// \pre as quadrangulate_polygons. \throw what `midpoint` throws, std::bad_alloc.
int split_odd_boundary_polygons(QuadMesh& q, const BoundaryMidpoint& midpoint, int max_size = 9);

/// A triangle left with one side on the boundary and quads on the other two: that side's ends c, x become one
/// boundary vertex at `midpoint` (the triangle goes, the faces around x take c; one vertex, two edges and one face
/// fewer). Done where c and x have no common neighbour but the triangle's third corner, at most once around each
/// vertex. x is left unused. Returns the number of triangles removed.
/// \pre as quadrangulate_polygons. \throw what `midpoint` throws, std::bad_alloc.
int collapse_boundary_sides(QuadMesh& q, const BoundaryMidpoint& midpoint);

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
