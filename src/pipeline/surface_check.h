#pragma once
// Did the remesh keep the surface it was given? The quad mesh must have the input's components, boundary loops and
// Euler characteristic (so the same genus), be manifold, and be all quads where the input is closed (issue: a
// remesh that changes topology silently is a wrong result, not a degraded one). The counts are mesh/surface_counts.h,
// the same ones `info` and `metrics` print.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/surface_counts.h"
#include "quad/extract_quads.h"

namespace quadcover {

/// Where the quad mesh differs from a clean remesh: a face that is not a quad, or a boundary loop the input has no
/// counterpart for (the output has more loops than the input).
struct SurfacePlace {
  std::string kind;  ///< "non-quad face" or "boundary loop"
  int face = -1;     ///< non-quad: the face's 1-based number in the written OBJ/PLY/OFF (-1 for a loop)
  int size = 0;      ///< sides of the face, edges of the loop
  Eigen::Vector3d at = Eigen::Vector3d::Zero();  ///< the face's or loop's vertex centroid, in model coordinates
};

struct SurfaceCheck {
  SurfaceCounts input, output;
  /// Same components, boundary loops and Euler characteristic; output manifold and oriented.
  bool same_topology = false;
  bool closed_all_quads = false;      ///< input closed ⇒ output closed, manifold and all quads (else true)
  std::vector<std::string> problems;  ///< one sentence per difference, for warnings
  std::vector<SurfacePlace> places;   ///< where (locate_surface_problems), in face order, then the loops
};

/// Compares the remeshed surface with the input. \pre every face index is in [0, num_vertices).
SurfaceCheck check_surface(const Mesh& input, int num_vertices, const std::vector<std::vector<int>>& faces);

/// Fills check.places from the quad mesh (V, faces) that check_surface compared: every non-quad face, and every
/// boundary loop of the output when it has more loops than the input (the new ones cannot be told apart).
/// \pre faces index rows of V; check is check_surface's result for these faces.
void locate_surface_problems(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces,
                             SurfaceCheck& check);

nlohmann::json to_json(const SurfaceCheck& check);  ///< \pre none

/// The warnings of a remesh (a degraded result is said, issue 18 item 9): each problem of the check ("remesh changed
/// the surface: ..."), one sentence listing the repairs the extraction made (fold repairs, cut-out triangles, torn
/// seams, failed traces, dropped faces, filled holes, ...) and, for an input with a boundary, the non-quads.
/// Empty for a closed all-quad result of a clean extraction. \pre none
std::vector<std::string> remesh_warnings(const SurfaceCheck& check, const ExtractionReport& extraction);

}  // namespace quadcover
