#pragma once
// The mesh cut open along a cut graph (thesis 1.3): every vertex is split into one cut-vertex per wedge of its fan
// between consecutive cut (or boundary) edges. Cut along a cut graph of cut_graph.h, each component becomes a
// topological disk on which curl*-free fields integrate (1.12).
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

struct CutMesh {
  /// #F by 3: the cut-vertex of each face corner (CornerData).
  Eigen::MatrixX3i corner_vertex;
  /// Per cut-vertex the original mesh vertex.
  std::vector<int> original_vertex;
  /// Boundary loops of the cut mesh, each a sequence of half-edges (face, corner): the boundary half-edge leaves
  /// the cut-vertex corner_vertex(face, corner) towards corner (corner + 1) % 3 of the same face, with the surface
  /// to its left. For a disk there is exactly one loop.
  std::vector<std::vector<Mesh::FanCorner>> boundary_loops;
  /// Per face, the index of its connected piece of the cut mesh (faces joined through uncut interior edges).
  Eigen::VectorXi face_piece;
  int num_pieces = 0;

  int num_vertices() const { return static_cast<int>(original_vertex.size()); }  ///< \pre none
  /// Number of edges of the cut mesh: interior cut edges count twice.
  int num_edges = 0;
  /// χ = v - e + f of the cut mesh (1 per disk). \pre the cut was made from mesh.
  int euler_characteristic(const Mesh& mesh) const { return num_vertices() - num_edges + mesh.num_faces(); }
};

/// Cuts the mesh along the edges with cut[e] != 0 (boundary edges are boundaries already).
/// cut  #E flags, e.g. CutGraph::cut. Cut-vertices are numbered by original vertex, then by fan order.
/// \pre mesh is valid. \throw InputError if cut has the wrong size.
CutMesh cut_mesh(const Mesh& mesh, const Eigen::VectorXi& cut);

}  // namespace quadcover
