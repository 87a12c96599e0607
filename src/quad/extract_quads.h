#pragma once
// Quad mesh extraction from an integer-grid map (thesis 2.1 requirement 3, 4.2.2; the method follows the idea of
// QEx, Ebke et al. 2013, written from scratch): the vertices are the integer points of φ (counted once, also on
// seams and at branch points), the edges are traced along integer iso-lines across triangles and seams using the
// transitions i^k z + c, and faces are read off the resulting rotation system. All predicates are exact (fixed
// point), so the result is consistent across seams. Folded or degenerate triangles and broken seams are cut out
// locally and reported; iso-lines that leave the surface end on the boundary, giving clipped polygons.
#include "common/progress.h"
#include "mesh/mesh.h"
#include "param/parameterization.h"
#include "quad/quad_mesh.h"

namespace quadcover {

struct ExtractOptions {
  /// Corner coordinates within `snap` grid units of a multiple of ½ are moved onto it (default 1e-6).
  double snap = 1e-6;
  /// Two sides of a seam that disagree by more than this (grid units) make the seam a cut (default 1e-5).
  double seam_tolerance = 1e-5;
  /// Faces with more corners than this are given up as broken (default 64).
  int max_face_size = 64;
  /// Untangle folded / degenerate triangles first by moving non-cone interior vertices (see repair_folds.h);
  /// what remains folded is cut out (default on).
  bool repair_folds = true;
  /// Collapse edges whose two ends the map sends to one point (see collapse_degenerate.h) before the repair
  /// (default on).
  bool collapse_zero_edges = true;
  /// Close small holes of cut-out folds, split interior even polygons into quads and merge adjacent odd ones
  /// first (see quadrangulate.h; default on).
  bool quadrangulate = true;
  /// Then the same with the clipped polygons at the boundary, after collapsing the triangles that iso-lines meeting
  /// the boundary at a shallow angle cut off (quadrangulate.h collapse_boundary_triangles, `with_boundary`; default
  /// on).
  bool quadrangulate_boundary = true;
};

/// What extraction found and repaired. A valid seamless map on a closed surface with integer branch points gives
/// all counters but `quads` zero.
struct ExtractionReport {
  int quads = 0, non_quads = 0;
  int grid_vertices = 0;         ///< output vertices at integer points
  int boundary_vertices = 0;     ///< output vertices where an iso-line meets the boundary
  int unfolded_triangles = 0;    ///< folded or degenerate triangles made valid by repair_folds
  int moved_vertices = 0;        ///< vertices repair_folds moved
  int collapsed_edges = 0;       ///< edges mapped to a point, collapsed (their two triangles removed)
  int flipped_triangles = 0;     ///< input triangles with negative parameter area (cut out)
  int degenerate_triangles = 0;  ///< input triangles with zero parameter area (cut out)
  int torn_seams = 0;            ///< edges whose transition does not hold (treated as boundary)
  int non_integer_translations = 0;  ///< transitions whose translation is not in Z[i]
  int failed_traces = 0;         ///< iso-line segments that could not be followed (e.g. into a non-integer branch point)
  int dropped_faces = 0;         ///< faces not emitted: a bounding segment failed, or an edge twice (near folds)
  int degenerate_faces = 0;      ///< faces with fewer than 3 distinct corners (dropped), but boundary slivers
  /// Faces whose corners are two boundary crossings only: a piece of the boundary beyond an iso-line that it crosses
  /// twice with no grid point between. Dropped: the quad mesh's boundary follows the iso-line there.
  int boundary_slivers = 0;
  int removed_spikes = 0;        ///< face loops x → v → x shortened (v an output vertex of valence 1, dropped)
  int removed_doublets = 0;      ///< interior vertices of valence 2 removed, their two faces merged (doublets.h)
  int split_vertices = 0;        ///< output vertices duplicated because cut-out folds pinched them
  int split_polygons = 0;        ///< interior polygons split into quads by diagonals (quadrangulate.h)
  int merged_polygons = 0;       ///< pairs of adjacent odd polygons merged before splitting
  int boundary_collapsed_triangles = 0;  ///< triangles cut off by iso-lines meeting the boundary, collapsed
  int boundary_added_vertices = 0;       ///< vertices put on the boundary to make an odd polygon even (then split)
  int boundary_split_polygons = 0;       ///< of those, polygons with sides on the boundary (clipped by it) split
  int boundary_merged_polygons = 0;      ///< of those, pairs with sides on the boundary merged
  int filled_holes = 0;          ///< small holes of cut-out folds closed by one polygon (away from the boundary)
  /// Parameter area of the triangles that were extracted (not cut out): the quad count of a valid closed map.
  double active_parameter_area = 0;
};

struct ExtractionResult {
  QuadMesh mesh;
  ExtractionReport report;
};

/// Extracts the quad mesh of an integer-grid map. Near-linear in #F + output size.
/// \pre mesh is a valid triangle mesh; param.uv is #F by 3; transitions are per edge in Parameterization's convention.
/// \throw InputError if param's array sizes do not match the mesh.
ExtractionResult extract_quads(const Mesh& mesh, const Parameterization& param, const ExtractOptions& options = {},
                               ProgressSink& progress = null_progress());

}  // namespace quadcover
