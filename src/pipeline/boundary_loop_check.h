#pragma once
// Which boundary loops of the input the quad mesh does not follow with quads, and why (issue 15 items 1 and 3). A
// loop is followed when its faces in the quad mesh are quads; it is not when its aligned lines (param/alignment.h)
// are not on integer iso-lines (the map's Curve::left_free_because says why), or when the loop is too short for a
// ring of quads at the density (a hole smaller than a few h). A loop is closed over when no boundary vertex of the
// quad mesh lies over it (a hole the quads cover, or one joined with another loop). Each loop of a remesh gets this
// record; the report lists them and the warnings name the loops with non-quad faces or closed over.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "param/alignment.h"
#include "param/parameterization.h"
#include "quad/quad_mesh.h"

namespace quadcover {

/// Below this length in grid units a loop cannot carry a ring of quads (4 sides of one quad).
inline constexpr double kShortestQuadLoop = 4.0;

struct BoundaryLoopCheck {
  int loop = 0;                       ///< the loop's number, 1-based, in the order of the loops' lowest vertex numbers
  int first_vertex = 0;               ///< its lowest vertex number of the input, 1-based as in the file
  Eigen::Vector3d at = Eigen::Vector3d::Zero();  ///< that vertex's position
  int edges = 0;                      ///< the input's boundary edges along it
  double length = 0;                  ///< its length in grid units (edges of the map's grid, h = map.edge_length)
  int lines = 0, enforced_lines = 0;  ///< aligned lines along it, and those on integer iso-lines
  int non_quads = 0;                  ///< faces of the quad mesh that are not quads and have a vertex on this loop
  bool closed_over = false;           ///< no boundary vertex of the quad mesh lies over the loop's triangles
  /// Empty when non_quads is 0 and the loop is not closed over; else why, and what would help: too short for a ring
  /// of quads, or the share of its edges (of the map's triangulation, which may split the input's) off the integer
  /// iso-lines and of the reason for most of them (Curve::left_free_because, or "not aligned with the field": on no
  /// aligned line).
  std::string reason;
};

/// One record per boundary loop of `mesh`, in the order of `loop` (the map's triangulation: the input or its
/// refinement, whose first `input_vertices` vertices are the input's). A non-quad face of `quads` counts for the loop
/// of the triangle (source_face) under each of its vertices on the quad mesh's boundary, once per loop; `alignment`
/// is what the job was given (the reason suggests round_with_periods when it was off, with its minimum length).
/// \pre map and quads were made on mesh.
std::vector<BoundaryLoopCheck> check_boundary_loops(const Mesh& mesh, int input_vertices, const Parameterization& map,
                                                    const QuadMesh& quads, const CurveAlignmentOptions& alignment);

/// The warnings: one sentence per loop closed over or with non-quad faces (closed over first, then the most non-quads
/// first), at most 5 (the rest counted). \pre none
std::vector<std::string> boundary_loop_warnings(const std::vector<BoundaryLoopCheck>& loops);

nlohmann::json to_json(const std::vector<BoundaryLoopCheck>& loops);  ///< \pre none

}  // namespace quadcover
