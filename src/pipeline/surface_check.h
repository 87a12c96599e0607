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

struct SurfaceCheck {
  SurfaceCounts input, output;
  /// Same components, boundary loops and Euler characteristic; output manifold and oriented.
  bool same_topology = false;
  bool closed_all_quads = false;      ///< input closed ⇒ output closed, manifold and all quads (else true)
  std::vector<std::string> problems;  ///< one sentence per difference, for warnings
};

/// Compares the remeshed surface with the input. \pre every face index is in [0, num_vertices).
SurfaceCheck check_surface(const Mesh& input, int num_vertices, const std::vector<std::vector<int>>& faces);

nlohmann::json to_json(const SurfaceCheck& check);  ///< \pre none

/// The warnings of a remesh (a degraded result is said, issue 18 item 9): each problem of the check ("remesh changed
/// the surface: ..."), one sentence listing the repairs the extraction made (fold repairs, cut-out triangles, torn
/// seams, failed traces, dropped faces, filled holes, ...) and, for an input with a boundary, the non-quads.
/// Empty for a closed all-quad result of a clean extraction. \pre none
std::vector<std::string> remesh_warnings(const SurfaceCheck& check, const ExtractionReport& extraction);

}  // namespace quadcover
