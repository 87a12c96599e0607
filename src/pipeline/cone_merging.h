#pragma once
// Branch points that the rounding puts on one lattice point (issue 14 item 3, beyond the thesis). Two adjacent
// branch points p, q with φ(p) = φ(q) hold every triangle containing both at zero area (param/untangle.h reports
// them as stuck): no map in the seamless subspace is injective there. Seen from outside the pair acts as one cone
// whose rotation is the product of theirs, so the field gets that cone: q's matching index modulo 4 moves to p
// along their edge (thesis 5.2.2), the field is smoothed again with the new matching (5.3) and the map is solved
// again. The quad mesh keeps the vertex the two cones shared; the map loses the collapsed triangles. Two branch
// points a few edges apart on one point are merged the same way, along the shortest edge path between them.
#include <vector>

#include "field/compute_frame_field.h"
#include "field/frame_field.h"
#include "mesh/mesh.h"
#include "param/parameterization.h"

namespace quadcover {

/// One merge: the branch point `from` gives its index modulo 4 (`quarters` ∈ {1, 2, 3}) to `into` (adjacent for the
/// coincident merges), along field/relocation.h's relocation_path.
struct ConeMerge {
  int from, into, quarters;
};

/// The merges that undo the map's stuck faces with two branch corners on one point: per such face (in face order)
/// the pair, `from` the higher vertex number, skipping pairs that share a vertex with an earlier merge or whose
/// edge is a boundary edge. \pre map was made on mesh (map.uv #F by 3).
std::vector<ConeMerge> coincident_cone_merges(const Mesh& mesh, const Parameterization& map);

/// How far close_coincident_merges looks for a branch point's partner: kNearRings, or also kFarRings.
enum class CoincidentReach { Near, Far };
/// Which near pairs close_coincident_merges takes: those beside a wrong winding, or also those with a folded common
/// neighbour (for a settled map: the untangling and the fold refinement have had their turn).
enum class CoincidentCause { WrongWindings, AlsoFolds };
inline constexpr int kNearRings = 3, kFarRings = 12;

/// Branch points a few edges apart on one lattice point (seen along a walk over the faces between them,
/// param/map_development.h): Near, within kNearRings of a branch point with a vertex within kNearRings that the map
/// winds a turn off (a cone's ring, or a regular vertex between them at 4π): the edge path between them closes on
/// itself in the map, and the turn stays off whatever untangling or edge split follows (seen on camelhead_boundary
/// and armadillo_86k: two +1/4 cones two edges apart; on bunny_20k_holes: a +1/4 and a −1/4 cone two edges apart),
/// or, with CoincidentCause::AlsoFolds, a pair with a common neighbour n that is no cone and a corner of a
/// non-positive triangle: the edges from n to
/// both map onto one segment, so the two parts of n's fan between them each turn by a multiple of 2π, and as they sum
/// to 2π one part has a triangle that is not positive, whatever the untangling does (seen on mech_holes_shark).
/// Far adds, for a branch point the map winds a turn off that has no near partner, a partner within kFarRings (seen
/// on camelhead_boundary: two −1/4 cones 7-8 rings apart on one point, one at π/2 with a vertex at 4π beside it).
/// Per such branch point in vertex order the first partner, `from` the higher number, each vertex in at most one
/// merge. \pre map was made on mesh (map.subspace filled).
std::vector<ConeMerge> close_coincident_merges(const Mesh& mesh, const Parameterization& map,
                                               CoincidentReach reach = CoincidentReach::Near,
                                               CoincidentCause cause = CoincidentCause::WrongWindings);

/// The moves that follow the map's winding (issue 14): a branch point c around which φ winds one turn too few or too
/// many gives its index modulo 4 to the nearest interior vertex n within 3 rings that is no branch point and carries
/// the opposite turn (a fake cone pair: the map gives c's cone angle ± 2π and n 2π ∓ 2π, every triangle positive),
/// along the shortest interior edge path; branch points in vertex order, each vertex in at most one move.
/// \pre map was made on mesh.
std::vector<ConeMerge> wound_cone_moves(const Mesh& mesh, const Parameterization& map);

/// Pairs of branch points with opposite quarter indices (q, −q) closer than `max_distance` along the paths a merge
/// takes (field/relocation.h relocation_reach): a grid of quad edge h puts every cone on a lattice point, so two cones
/// less than h apart land on one point or on neighbouring ones, and the map folds or stretches between them. Merging
/// such a pair cancels it (index 0). Pairs in order of distance (ties by vertex numbers), each vertex in at most one
/// merge, `from` the higher number. On a component meshed ρ times finer (DensityOptions::component_density, empty:
/// 1 everywhere) its quad edge is h / ρ, and so is the distance.
/// \pre points are interior vertices of mesh (field/indices.h branch_points), max_distance >= 0.
std::vector<ConeMerge> close_opposite_cone_merges(const Mesh& mesh, const std::vector<BranchPoint>& points,
                                                  double max_distance,
                                                  const std::vector<double>& component_density = {});

/// `field` with the merges applied to its matching and its frames smoothed again for that matching (the field
/// stage's weights, trusted and constrained faces and λ; field/smoothing.h).
/// \throw NumericalError if the smoothing system cannot be factored.
FrameField merge_cones(const Mesh& mesh, const FrameFieldResult& stage, const FrameField& field, double lambda,
                       const std::vector<ConeMerge>& merges);

}  // namespace quadcover
