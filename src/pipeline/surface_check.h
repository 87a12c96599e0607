#pragma once
// Did the remesh keep the surface it was given? The quad mesh must have the input's components, boundary loops and
// Euler characteristic (so the same genus), be manifold, and be all quads where the input is closed (issue: a
// remesh that changes topology silently is a wrong result, not a degraded one).
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

/// The topology of a surface, as counted from its faces.
struct SurfaceCounts {
  int components = 0;            ///< connected through shared vertices
  int boundary_loops = 0;        ///< cycles of edges with one face
  int euler_characteristic = 0;  ///< V − E + F over the vertices that faces use
  int non_manifold_edges = 0, non_manifold_vertices = 0;
  int non_quads = 0;
};

/// Counts of a polygon mesh (any face sizes) over `num_vertices` vertices. Linear time.
/// \pre every index is in [0, num_vertices).
SurfaceCounts surface_counts(int num_vertices, const std::vector<std::vector<int>>& faces);
/// Counts of a triangle mesh (non_quads = 0: a triangle input is not judged by its face sizes).
SurfaceCounts surface_counts(const Mesh& mesh);

struct SurfaceCheck {
  SurfaceCounts input, output;
  bool same_topology = false;         ///< same components, boundary loops and Euler characteristic, output manifold
  bool closed_all_quads = false;      ///< input closed ⇒ output closed, manifold and all quads (else true)
  std::vector<std::string> problems;  ///< one sentence per difference, for warnings
};

/// Compares the remeshed surface with the input.
SurfaceCheck check_surface(const Mesh& input, int num_vertices, const std::vector<std::vector<int>>& faces);

nlohmann::json to_json(const SurfaceCheck& check);

}  // namespace quadcover
