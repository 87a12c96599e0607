#pragma once
// Closed crease loops and the side of a short one that the field leaves free (beyond the thesis; issue 15 item 3).
// The rim of a bolt hole through a plate is a closed loop of sharp edges between the plate, where the loop turns by
// a whole turn, and the hole's wall, where it runs straight (geodesic turning 0). Aligning the field to the rim on
// the plate side makes it polar around the hole, with its four −1/4 cones off the rim; the curl-free map then
// shrinks the quads towards the hole like log r, and with a rim only a few quads around the cones crowd onto
// lattice points (wrong windings). Leaving the plate side of a short rim free, the field stays parallel there and
// the cones sit at the rim: the hole comes out as a square of quads in an even grid (BENCHMARKS.md, "Short crease
// loops as square holes").
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

/// A closed curve of sharp edges on which every vertex has exactly two sharp edges, in order: edge i joins vertex i
/// and i + 1 (mod n). Geodesic turning on either side: Σ (π − the angle of that side's faces at the vertex), so
/// about ±2π on the side of a plate round a hole and 0 on the side of a straight wall.
struct CreaseLoop {
  std::vector<int> vertices, edges;
  double length = 0;
  double turning_left = 0;   ///< on the side of the faces that have edge i as (vertex i, vertex i + 1)
  double turning_right = 0;  ///< on the other side
};

/// The closed crease loops of `sharp_edges` (interior edges), in the order of their lowest sharp edge.
/// \pre sharp_edges are interior edges of mesh.
std::vector<CreaseLoop> closed_crease_loops(const Mesh& mesh, const std::vector<int>& sharp_edges);

/// Whether the field leaves the left (+1) or right (−1) side of `loop` free, or neither (0): a loop shorter than
/// max_length that turns by more than half a turn on that side and by less than a quarter turn on the other.
/// \pre none
int free_side(const CreaseLoop& loop, double max_length);

/// Per face, the loop edges whose alignment the face leaves (those on the free_side of their loop, for loops shorter
/// than max_length): bit k stands for edge FE(f, k). \pre loops from closed_crease_loops(mesh, …).
std::vector<unsigned char> freed_loop_sides(const Mesh& mesh, const std::vector<CreaseLoop>& loops, double max_length);

}  // namespace quadcover
