#pragma once
// Doublets (beyond the thesis; issue 14: all-quad, valid output): an interior vertex of the quad mesh that only two
// faces use. The two faces then share both of its edges: geometrically one cell folded around a point, which the
// map makes where its angle sum is π (a branch point of index +1/2, or one wound a turn short beside a vertex wound
// a turn too far, param/ring_winding.h). A vertex of valence 2 is a defect of any quad mesh; remeshers remove it by
// merging its two faces. Here the vertex goes and its two faces become one polygon, the union of their other sides;
// a chain of such vertices between the same two faces goes with it (their sides fold back on themselves). Two quads
// become one quad; a quad and a larger polygon become a polygon of two sides fewer, for quadrangulate.h to split.
// Euler characteristic, components and boundary loops are unchanged (per vertex removed: one vertex and two edges
// fewer, and the two faces one).
#include "quad/quad_mesh.h"

namespace quadcover {

/// Removes the doublets of q: an interior vertex v (every edge at v has two faces) used by exactly two faces A and
/// B is dropped and A and B are replaced by their union, where the union is a simple polygon (no corner twice) of at
/// least four corners and merging does not add a non-quad: the union has four corners, or A or B was not a quad
/// already; and where every removed vertex lies within max_offset × (the union's mean side) of the union (fanned from
/// its centroid): at a sharp tip, where the doublet's vertex carries the surface, it stays. Repeated until no doublet
/// is left that can go. Removed vertices are left unused (remove_unused_vertices).
/// \return the number of vertices removed. \pre q is an oriented manifold polygon mesh (every face index <
/// q.num_vertices()). Deterministic (vertices in index order). \throw only std::bad_alloc.
int remove_doublets(QuadMesh& q, double max_offset = 0.5);

}  // namespace quadcover
