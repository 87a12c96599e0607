#pragma once
// Per-vertex quality of a polygon (quad) mesh, for viewers (PLY `quality` / `valence` vertex properties): the
// worst corner angle at a vertex and its valence.
#include <Eigen/Core>
#include <vector>

namespace quadcover {

struct VertexQuality {
  /// #V, degrees: max over the vertex's face corners of |corner angle - (n - 2)·180°/n| for an n-gon corner (the
  /// deviation from 90° in a quad); 0 for a vertex in no face. Large = a sheared or folded quad at the vertex.
  Eigen::VectorXd worst_angle_deviation;
  /// #V: number of distinct edges at the vertex (4 at a regular interior vertex of a quad mesh, 0 if unused).
  Eigen::VectorXi valence;
};

/// Computes both for V (#V by 3) and faces (0-based vertex indices, each face >= 3 corners). A corner with a
/// zero-length edge counts as a deviation of 180°.
/// \pre face indices in [0, #V).
VertexQuality vertex_quality(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces);

}  // namespace quadcover
