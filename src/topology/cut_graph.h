#pragma once
// Shortest cut graphs (thesis 1.3.1): Algorithm 1.16 (Erickson–Whittlesey tree–cotree) with the extension of
// [KNP10] to a set B of base vertices and to boundaries: all vertices of B and of the boundary are identified to
// one point (a multi-source shortest-path forest), the algorithm runs, and the identification is undone.
#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

struct CutGraphOptions {
  /// Positive weight per edge (#E). Default (empty): Euclidean edge lengths (thesis 1.3.1).
  std::optional<Eigen::VectorXd> edge_weights;
};

/// One path σ(e) of the cut graph: the non-tree, non-cotree edge e plus the shortest-path-tree paths from its
/// endpoints to their roots. Both endpoints are sources (base or boundary vertices, or the chosen root of a closed
/// component without base vertices); no other vertex of the path is a source.
struct CutPath {
  std::vector<int> vertices;  ///< v_0 … v_m, v_0 = root of E(e,0), v_m = root of E(e,1) (may coincide: a loop)
  std::vector<int> edges;     ///< m edges, edges[i] joins vertices[i] and vertices[i+1]
  int leftover_edge = -1;     ///< e (neither in T nor crossed by T*)
  double length = 0;          ///< |σ(e)|, sum of the edge weights
};

struct CutGraph {
  /// #E: 1 iff the edge lies on some path (the cut graph K). Boundary edges are never flagged.
  Eigen::VectorXi cut;
  /// The output paths σ(e), one per leftover edge, ordered by leftover edge index. They may share tree edges.
  /// Per component: 2g + b + |B| - 1 paths (b boundary loops, |B| interior base vertices; a closed component
  /// without base vertices counts its root as the one base vertex).
  std::vector<CutPath> paths;
  /// Sorted sources: the base vertices, all boundary vertices, and one root (smallest vertex index) per closed
  /// component that contains no base vertex.
  std::vector<int> sources;
  /// Shortest-path forest T: per vertex the tree edge towards its root (-1 at sources), its root, the distance.
  Eigen::VectorXi parent_edge;
  Eigen::VectorXi root;
  Eigen::VectorXd distance;
  /// #E: 1 iff e* belongs to the maximum spanning tree T* of the dual of G \ T (interior edges only).
  Eigen::VectorXi cotree;
  /// Total weight of the cut graph (each cut edge counted once).
  double total_length = 0;
  /// Number of homology generators the cut carries (see homology.h): per component 2g when closed, 2g + b - 1 with
  /// b > 0 boundary loops. The other paths only join base vertices and boundary loops.
  int num_loops = 0;
};

/// Shortest cut graph based at B ∪ ∂M (Algorithm 1.16 with [KNP10]); deterministic (ties broken by index).
/// Cutting the mesh along `cut` leaves one topological disk per component, except a closed genus-0 component with
/// at most one base vertex, which stays uncut (it is simply connected).
/// base  interior or boundary vertex indices (duplicates allowed); boundary vertices are always sources.
/// \pre  mesh is a valid triangle mesh. \throw InputError if a base vertex or the weights are invalid.
/// Runs in O(n log n).
CutGraph cut_graph(const Mesh& mesh, std::span<const int> base = {}, const CutGraphOptions& options = {});

}  // namespace quadcover
