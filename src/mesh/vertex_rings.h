#pragma once
// A set of vertices grown by rings over the faces: the untangler's regions around folds and the curve constraints
// given up around wrong windings (param/untangle.h, param/ring_winding.h); the faces a few rings around a vertex
// (param/map_development.h, param/cone_disk_layout.h).
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

/// `in` (#V flags) grown `rings` times by every vertex of a face that has a vertex in the set. \pre in is #V.
std::vector<char> grow_vertex_rings(const Mesh& mesh, std::vector<char> in, int rings);

/// The faces touching the vertices within `rings` rings of p (ascending); work proportional to them.
/// \pre 0 <= p < #V, rings >= 0.
std::vector<int> faces_within_rings(const Mesh& mesh, int p, int rings);

}  // namespace quadcover
