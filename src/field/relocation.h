#pragma once
// Branch point relocation (thesis 5.2.2): moving the matching index from one vertex to another along an edge path.
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "field/frame_field.h"
#include "mesh/mesh.h"

namespace quadcover {

/// Shortest edge path (by length, Dijkstra; ties broken by vertex index) from interior vertex p to vertex q,
/// as a vertex sequence p, ..., q. Only interior edges are used and only the endpoints may be boundary
/// vertices, so that every crossed edge carries a matching.
/// \throw std::invalid_argument if p is a boundary vertex or q is unreachable.
std::vector<int> relocation_path(const Mesh& mesh, int p, int q);

/// The vertices that relocation paths from interior vertex p reach within `radius` (path length along the same
/// interior edges, through interior vertices only), with their distances, nearest first (Dijkstra, bounded): each
/// has a relocation_path from p. \pre p an interior vertex of mesh, radius >= 0.
std::vector<std::pair<int, double>> relocation_reach(const Mesh& mesh, int p, double radius);

/// The matching changes that move `quarters` quarter units of matching index (Def. 3.2) from path.front() to
/// path.back(): `quarters` is added to the matching across every path edge in the direction that crosses it
/// from right to left when walking from p to q (with our sign of m, see field/frame_field.h). The matching index
/// of p decreases by `quarters`, that of q increases by it, all others are unchanged (the two path edges at an
/// intermediate vertex cancel in its loop sum).
/// \pre path = relocation_path(mesh, …). \throw std::invalid_argument if two consecutive path vertices share no interior edge.
std::vector<MatchingChange> relocation_changes(const Mesh& mesh, const std::vector<int>& path, int quarters);

/// Moves the whole matching index 4·ind_p(m) of p to q along relocation_path(p, q) (thesis 5.2.2) and returns the
/// changes applied to `matching` (#E), e.g. to feed FrameSmoother::change_matching for the re-solve.
/// \pre matching has #E entries. \throw std::invalid_argument as relocation_path.
std::vector<MatchingChange> relocate_branch_point(const Mesh& mesh, Eigen::VectorXi& matching, int p, int q);

}  // namespace quadcover
