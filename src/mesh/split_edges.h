#pragma once
// Local refinement of a triangle mesh: edges split at their midpoints (no vertex moves, the surface is unchanged).
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

/// A refined triangulation: the input's vertices first (same numbers), then one new vertex per split edge in the
/// order the edges were given; parent_face[t] is the input face that new face t lies in.
struct SplitMesh {
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  std::vector<int> parent_face;
};

/// Splits each listed edge at its midpoint. A face with k split edges becomes k + 1 triangles, a fan from its first
/// split edge's midpoint (in the face's corner order), so every new triangle keeps the face's orientation and none
/// is degenerate. Faces without split edges keep their number order (they come first, in input order).
/// \pre every entry is an edge of mesh, without repeats. \throw std::invalid_argument otherwise.
SplitMesh split_edges_at_midpoints(const Mesh& mesh, const std::vector<int>& edges);

}  // namespace quadcover
