#pragma once
// The output of quad extraction (thesis 2.1, requirement 3: parameter lines partition the surface into quads):
// a polygon mesh whose vertices are integer points of the map (plus boundary crossings) and whose edges follow
// the integer iso-lines. Also a combinatorial check of the polygon mesh (manifoldness, Euler characteristic).
#include <Eigen/Core>
#include <complex>
#include <vector>

namespace quadcover {

struct QuadMesh {
  Eigen::MatrixX3d V;                    ///< #V by 3 positions on the input surface
  std::vector<std::vector<int>> faces;   ///< polygons, counter-clockwise around the outward normal
  /// #V: the vertex's parameter point φ in the chart of `source_face` (a Gaussian integer for grid vertices).
  Eigen::VectorXcd uv;
  Eigen::VectorXi source_face;           ///< #V: input triangle containing the vertex
  /// #V: 1 for integer grid points, 0 for points where an iso-line meets the boundary (clipped polygons).
  Eigen::VectorXi on_grid;

  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_faces() const { return static_cast<int>(faces.size()); }
  int num_quads() const;  ///< faces with exactly four corners
};

/// Combinatorial structure of a polygon mesh.
struct PolygonTopology {
  int vertices = 0, edges = 0, faces = 0;  ///< edges: distinct undirected vertex pairs
  int boundary_edges = 0;                  ///< edges with a single face
  int non_manifold_edges = 0;              ///< edges in more than two faces, or twice in the same direction
  int non_manifold_vertices = 0;           ///< vertices whose faces form more than one fan
  int isolated_vertices = 0;               ///< vertices in no face
  int degenerate_faces = 0;                ///< faces with fewer than 3 corners or a repeated corner
  int euler_characteristic = 0;            ///< V - E + F (isolated vertices excluded)
  bool manifold() const { return non_manifold_edges == 0 && non_manifold_vertices == 0 && degenerate_faces == 0; }
  bool closed() const { return boundary_edges == 0; }
};

/// Counts the above for faces over `num_vertices` vertices. Linear time.
/// \pre every face index lies in [0, num_vertices). \throw only std::bad_alloc.
PolygonTopology polygon_topology(int num_vertices, const std::vector<std::vector<int>>& faces);

/// Where two faces use the same directed edge (possible next to cut-out folds), keeps the smallest face and drops
/// the others. Returns the number of dropped faces.
/// \pre every face index < q.num_vertices(). \throw only std::bad_alloc.
int drop_faces_on_duplicate_edges(QuadMesh& q);

/// Gives each fan of faces around a vertex its own copy of the vertex (a vertex pinched between holes).
/// Returns the number of vertices added.
/// \pre every face index < q.num_vertices(). \throw only std::bad_alloc.
int split_pinched_vertices(QuadMesh& q);

/// Cuts spikes out of a face loop: where the loop runs x → v → x (v is an end of the graph, a vertex of valence 1),
/// v and the repeated x are removed. Returns the number of spikes removed.
int remove_spikes(std::vector<int>& loop);

/// Removes the vertices used by no face and numbers the others in order of first use by the faces.
/// Returns the number of vertices removed.
/// \pre every face index < q.num_vertices(). \throw only std::bad_alloc.
int remove_unused_vertices(QuadMesh& q);

}  // namespace quadcover
