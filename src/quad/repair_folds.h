#pragma once
// Local untangling of an integer-grid map before extraction (thesis 2.1 requirement 2, det Dφ > 0): vertices of
// folded or degenerate triangles are moved to the average of their one-ring, seen in the vertex's own chart and
// written back consistently into every chart across seams, so the map stays seamless. Cones (vertices where the
// charts around do not close up to the identity) and boundary vertices never move, so grid-aligned branch points
// and boundaries are preserved. What Tutte relaxation leaves folded is then moved into the kernel of its one-ring.
#include "mesh/mesh.h"
#include "param/parameterization.h"

namespace quadcover {

struct FoldRepairOptions {
  /// Vertices of triangles whose signed parameter area is <= min_area (grid units², default 1e-9) are moved.
  double min_area = 1e-9;
  /// Gauss–Seidel sweeps per round (default 20); each round grows the moving set by one ring (default 6 rounds).
  int sweeps = 20;
  int rounds = 6;
  /// Then up to `kernel_sweeps` sweeps moving each regular vertex near a bad triangle into the kernel of its
  /// one-ring (never creating a bad triangle), over a neighbourhood growing up to `max_ring` rings (default 40, 4).
  int kernel_sweeps = 40;
  int max_ring = 4;
};

struct FoldRepairResult {
  Eigen::MatrixX3cd uv;      ///< repaired per-corner coordinates
  int bad_before = 0;        ///< triangles with signed area <= 0 before
  int bad_after = 0;         ///< ... after the repair
  int moved_vertices = 0;
};

/// \pre param.uv is #F by 3 and transitions are per edge (Parameterization's convention).
FoldRepairResult repair_folds(const Mesh& mesh, const Parameterization& param, const FoldRepairOptions& options = {});

}  // namespace quadcover
