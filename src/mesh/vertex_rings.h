#pragma once
// A set of vertices grown by rings over the faces: the untangler's regions around folds and the curve constraints
// given up around wrong windings (param/untangle.h, param/ring_winding.h).
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

/// `in` (#V flags) grown `rings` times by every vertex of a face that has a vertex in the set. \pre in is #V.
std::vector<char> grow_vertex_rings(const Mesh& mesh, std::vector<char> in, int rings);

}  // namespace quadcover
