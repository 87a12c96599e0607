#pragma once
// Tangential smoothing of an extracted quad mesh on the input surface (beyond the thesis, as remeshers such as
// Instant Meshes and QuadWild finish): local/global rounds in which every quad is fitted by a square — of the
// mesh's mean edge length h (rigid) blended with its own best-fit size (conformal) — and every free vertex moves,
// within its tangent plane, to the mean of the corners its quads ask for, then back onto the input surface
// (closest point). The connectivity is unchanged; the integer-grid map only decides it.
#include "common/progress.h"
#include "field/feature_alignment.h"
#include "mesh/mesh.h"
#include "param/parameterization.h"
#include "quad/quad_mesh.h"

namespace quadcover {

struct QuadSmoothingOptions {
  int iterations = 20;  ///< local/global rounds (0 = off); the default of `remesh`
  /// Weight of the common size h against each quad's own size in its target square: 1 evens out edge lengths
  /// (rigid), 0 only squares the quads up (conformal); 0.5 by default (BENCHMARKS.md, "Option defaults").
  double rigidity = 0.5;
  /// Fraction of the way to the target taken per round (damped Jacobi).
  double step = 0.5;
  /// The input's sharp feature edges (field/feature_alignment.h); the remesh job uses its options.param.features
  /// (`--feature-angle`, `--features`). Vertices within feature_tolerance h of one are on the feature.
  FeatureOptions features;
  double feature_tolerance = 1e-6;
  /// Interior vertices within this many h of a sharp feature curve are snapped onto it and then slide along it
  /// (their moves are projected onto the feature polyline) so that quad edges run on the crease; 0 = off (vertices
  /// on a feature do not move). A vertex is not snapped where that would shorten an edge of its quads below h/2
  /// or put more than two corners, or two opposite ones, of a quad on features. Vertices at feature corners (curve
  /// ends, turns > 40°) do not move. Moving a row by up to this much stretches the quads beside it (the measured trade
  /// of coverage against RSD: BENCHMARKS.md, "Feature fidelity").
  double feature_snap = 0.4;
  /// Boundary vertices slide along the input's boundary (their moves are projected onto the boundary polyline),
  /// but not past a corner of it (a turn of more than 40° at an input vertex) nor away from one; corners of the quad
  /// mesh's boundary (one face) and of non-quads stay. false: every boundary vertex stays where extraction put it.
  bool slide_boundary = true;
};

struct QuadSmoothingReport {
  int iterations = 0;
  double edge_length = 0;        ///< h: mean edge length of the quads before smoothing
  int fixed_vertices = 0;        ///< on the boundary, at feature corners or corners of non-quads: not moved
  int boundary_vertices = 0;     ///< on the boundary and sliding along it (QuadSmoothingOptions::slide_boundary)
  int feature_vertices = 0;      ///< snapped onto a sharp feature curve and sliding along it
  int rejected_moves = 0;        ///< moves undone because they would have turned a corner of a quad inside out
  double mean_displacement = 0;  ///< mean distance of a free vertex from where extraction put it, in units of h
  double max_displacement = 0;   ///< the largest such distance, in units of h
};

/// Smooths q in place. Boundary vertices of q slide along the input's boundary (slide_boundary) and corners of
/// non-quad faces stay where they are; a move that
/// would make a corner of an incident quad point against the surface normal is undone. Updates V, source_face
/// and uv (φ at the new point, so grid vertices are no longer at integer points). Deterministic; O(#V log #F) a
/// round. \pre q was extracted from `param` on `mesh`.
/// \throw InputError if q has no source face / uv per vertex or param.uv does not match the mesh.
QuadSmoothingReport smooth_quads(QuadMesh& q, const Mesh& mesh, const Parameterization& param,
                                 const QuadSmoothingOptions& options, ProgressSink& progress = null_progress());

}  // namespace quadcover
