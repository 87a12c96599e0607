#pragma once
// The output of quad extraction (thesis 2.1, requirement 3: parameter lines partition the surface into quads):
// a polygon mesh whose vertices are integer points of the map (plus boundary crossings) and whose edges follow
// the integer iso-lines, and the clean-ups extraction applies to it. Its topology is counted by
// mesh/surface_counts.h, the one count info, metrics, the reports and the tests use.
#include <Eigen/Core>
#include <complex>
#include <utility>
#include <vector>

namespace quadcover {

struct QuadMesh {
  Eigen::MatrixX3d V;                    ///< #V by 3 positions on the input surface
  std::vector<std::vector<int>> faces;   ///< polygons, counter-clockwise around the outward normal
  /// #V: the vertex's parameter point φ in the chart of `source_face` (a Gaussian integer for grid vertices).
  Eigen::VectorXcd uv;
  Eigen::VectorXi source_face;           ///< #V: input triangle containing the vertex
  /// #V: 1 for integer grid points, 0 for points on the boundary (where an iso-line meets it, or added on it when
  /// the clipped polygons are made quads, quadrangulate.h).
  Eigen::VectorXi on_grid;

  int num_vertices() const { return static_cast<int>(V.rows()); }  ///< \pre none
  int num_faces() const { return static_cast<int>(faces.size()); }  ///< \pre none
  int num_quads() const;  ///< faces with exactly four corners \pre none
};

/// The undirected edges {a, b} (a < b) of polygon faces, each with the number of faces that have it, sorted by edge.
/// \pre none
std::vector<std::pair<std::pair<int, int>, int>> polygon_edge_uses(const std::vector<std::vector<int>>& faces);

/// #V flags: 1 for the vertices on an edge that only one face has (the quad mesh's boundary). \pre every face index
/// < q.num_vertices().
std::vector<char> quad_boundary_vertices(const QuadMesh& q);

/// Where two faces use the same directed edge (possible next to cut-out folds), keeps the smallest face and drops
/// the others. Returns the number of dropped faces.
/// \pre every face index < q.num_vertices(). \throw only std::bad_alloc.
int drop_faces_on_duplicate_edges(QuadMesh& q);

/// Gives each fan of faces around a vertex its own copy of the vertex (a vertex pinched between holes).
/// Returns the number of vertices added.
/// \pre every face index < q.num_vertices(). \throw only std::bad_alloc.
int split_pinched_vertices(QuadMesh& q);

/// Cuts spikes out of a face loop: where the loop runs x → v → x (v is an end of the graph, a vertex of valence 1),
/// v and the repeated x are removed. Returns the number of spikes removed. \pre none
int remove_spikes(std::vector<int>& loop);

/// Removes the vertices used by no face and numbers the others in order of first use by the faces.
/// Returns the number of vertices removed.
/// \pre every face index < q.num_vertices(). \throw only std::bad_alloc.
int remove_unused_vertices(QuadMesh& q);

}  // namespace quadcover
