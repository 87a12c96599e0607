#pragma once
// A seamless map carried over to a midpoint refinement of its triangulation (mesh/split_edges.h; beyond the thesis,
// issue 14 item 3). The refinement moves no vertex and the map stays the same piecewise linear function: every child
// triangle takes its parent's map restricted to it (a midpoint gets the mean of its edge's endpoints), so the seams,
// periods, branch points (thesis 4.2) and curve constraints are those of the coarse map. What the map needs on the
// finer mesh follows from the parent face:
//  - frames: a child inherits its parent's frame (same plane; only the face basis changes);
//  - matching and transitions (Def. 3.1, (4.2)): the identity across a new edge inside a parent face, the parent
//    edge's across each half of a split edge (inverted where the half is seen from the other side);
//  - the seamless subspace (Parameterization::Subspace): children's corners keep their parent's layer λ; a midpoint
//    is a new regular vertex, free unless its edge lies on an enforced curve, where the curve's coordinate is held.
// Branch points stay on the original vertices (a midpoint has index 0: its angle sum is 2π and the transitions
// around it compose to the identity).
#include <array>
#include <vector>

#include "field/frame_field.h"
#include "mesh/mesh.h"
#include "param/parameterization.h"

namespace quadcover {

struct SplitMap {
  Mesh mesh;              ///< the refined triangulation: the coarse vertices first, then one midpoint per split edge
  FrameField field;       ///< the coarse field on the children
  Parameterization map;   ///< the coarse map on the children (per-face and per-edge data re-indexed)
  std::vector<int> parent_face;               ///< per refined face: its coarse face
  std::vector<std::array<int, 2>> split;      ///< per midpoint (vertex #V + k): the coarse vertex pair of its edge
};

/// Splits `edges` of `mesh` at their midpoints and carries `field` and `map` over (see above). The untangling
/// record of `map` is copied as it is (its face lists still name coarse faces).
/// \pre field and map belong to mesh, map.subspace is filled; edges are distinct edges of mesh.
/// \throw std::invalid_argument if an entry of edges is not an edge of mesh or repeats.
SplitMap split_map(const Mesh& mesh, const FrameField& field, const Parameterization& map,
                   const std::vector<int>& edges);

}  // namespace quadcover
