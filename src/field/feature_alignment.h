#pragma once
// Alignment to boundary curves and sharp feature edges (beyond the thesis): faces along such curves get their
// cross fixed to the curve direction; they count as trusted and smoothing keeps them fixed.
#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

/// A sharp feature given by the user: the segment of an edge of the input mesh.
struct FeatureSegment {
  Eigen::Vector3d a, b;
};

struct FeatureOptions {
  bool boundaries = true;  ///< constrain faces that have a boundary edge
  /// An interior edge is a sharp feature when the angle between its two face normals |β_e| exceeds this many
  /// degrees. 35° catches machined edges (typically 45°-90°) but not the folds of a curved organic mesh at
  /// usual resolution (a few degrees per edge). <= 0 disables sharp features.
  double sharp_angle_degrees = 35.0;
  /// A sharp edge counts only as part of a feature curve of at least this many sharp edges, consecutive ones
  /// continuing each other (turning by less than 40° at their common vertex). Isolated sharp edges are noise
  /// on coarse organic meshes; CAD creases are long chains (BENCHMARKS.md, "Option defaults"). 1 keeps every
  /// sharp edge.
  int min_curve_edges = 8;
  /// A sharp edge on a shorter chain still counts when every other edge of its two faces bends by less than this many
  /// degrees (a crisp crease between flat sides, as on a machined part, not a fold in a scan's noise), it lies between
  /// two corners of the network of such edges and kept chains, and at least min_curve_edges such edges are joined to
  /// it: the short flanks and tooth tops of a gear (BENCHMARKS.md, "Crisp short creases"). 0 = chains only.
  double crisp_crease_degrees = 5.0;
  /// Crisp short creases on a chain (sharp edges continuing each other) shorter than this (model units; 0 = any) are
  /// not followed: the pipeline sets it to the quad edge length the user asked for (--faces, --edge-length), since
  /// shorter creases crowd the field's cones (a gear's teeth at a few hundred quads); 0 at the default density.
  double crisp_min_length = 0;
  /// Closed crease loops shorter than this (model units; 0 = none) that turn by a whole turn on one side and run
  /// straight on the other (the rim of a small hole through a plate, field/crease_loops.h) are followed on the
  /// straight side only: the turning side's faces along them are left free. The pipeline sets it from the density.
  double free_short_loops_below = 0;
  /// Sharp features given by the user (`--features FILE`): when set, the sharp edges are exactly the edges lying on
  /// these segments (both halves of a split edge too, so a refined mesh keeps them), whatever their dihedral angle;
  /// sharp_angle_degrees and min_curve_edges are then not used. Empty: no sharp features.
  std::optional<std::vector<FeatureSegment>> given;
};

/// Whether `options` ask for any sharp feature (given segments, or a positive angle). \pre none
bool has_sharp_features(const FeatureOptions& options);

/// The first edge feature_segments refused: its position in the list, why, and for a vertex problem the vertex.
struct RefusedFeatureEdge {
  enum class Why { kNone, kNoSuchVertex, kVertexInNoFace, kNotAnEdge };
  Why why = Why::kNone;
  int position = -1;
  int vertex = -1;  ///< the input's vertex number (0-based) for kNoSuchVertex and kVertexInNoFace
};

/// The segments of the given edges, for FeatureOptions::given. `edges` are vertex pairs of the input (a mesh file,
/// or the rows of V), mapped to `mesh` by `mesh_vertex_of_input` (-1: a vertex in no face, dropped by the mesh).
/// Stops at the first pair naming a vertex the input lacks or uses in no face, or two vertices not joined by an edge
/// of the mesh, and says which in `refused` (why = kNone when all are edges). \pre the numbers are >= 0.
std::vector<FeatureSegment> feature_segments(const Mesh& mesh, const std::vector<int>& mesh_vertex_of_input,
                                             const std::vector<std::pair<int, int>>& edges,
                                             RefusedFeatureEdge& refused);

struct FeatureConstraints {
  std::vector<char> constrained;   ///< #F: 1 if the face's cross is fixed
  Eigen::VectorXcd direction;      ///< #F: unit direction of the curve in the face basis (0 where unconstrained)
  std::vector<int> source_edge;    ///< #F: the edge the face is aligned with, -1 where unconstrained
  std::vector<int> feature_edges;  ///< sharp interior edges, ascending (boundary edges not listed)
};

/// The sharp interior edges feature_constraints follows (its feature_edges, ascending), and how many of them only as
/// crisp short creases (FeatureOptions::crisp_crease_degrees).
struct FollowedSharpEdges {
  std::vector<int> edges;
  int crisp = 0;
};

/// The sharp edges feature_constraints follows, without the faces' constraints. \pre none
FollowedSharpEdges followed_sharp_edges(const Mesh& mesh, const FeatureOptions& options);

/// Finds boundary and sharp edges (detected from the dihedral angle, or the given ones) and, for every face having
/// one, the direction its cross must contain.
/// A face with several such edges follows the strongest (boundary counts as π, a sharp edge as |β_e|; ties:
/// longer edge, then lower face-edge index): a cross cannot contain two non-perpendicular directions. \pre none
FeatureConstraints feature_constraints(const Mesh& mesh, const FeatureOptions& options = {});

}  // namespace quadcover
