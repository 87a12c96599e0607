#pragma once
// Targeted refinement for the triangles the untangling leaves non-positive (issue 14 item 3, beyond the thesis).
// The untangler (param/untangle.h) optimizes in the seamless affine subspace of one triangulation; a triangle too
// coarse for the lattice constraints around it has no positive position there: an ear whose three corners the
// curve constraints hold on one integer iso-line (its third edge is free), a fan around a branch point too small
// for its cone angle (the angles at a cone of index k/4 must add up to (4 − k)·π/2, each below π), a sliver between
// pinned corners. Splitting the edges of such triangles adds free vertices: each round carries the map over to the
// finer mesh unchanged (pipeline/split_map.h: same transitions, periods, branch points and curves) and untangles it
// there. Where the constraints themselves hold a face at zero area (all its corners pinned to one line: a curve
// that turns back along its line, two close parallel curves snapped to one integer, a closed triangle of feature
// edges), no refinement helps: the curve pins of one of its corners are given up first (release_stuck_corners;
// the curve leaves its line there, the report's aligned_curves deviation says by how much). A round is kept only
// if it leaves fewer non-positive triangles; after a round without progress the next one also splits the 1-ring,
// after a second one it also releases the curve pins of the remaining faces' corners, after a third it stops.
#include <array>
#include <memory>
#include <vector>

#include "common/progress.h"
#include "field/frame_field.h"
#include "mesh/mesh.h"
#include "param/parameterization.h"
#include "param/untangle.h"

namespace quadcover {

struct FoldRefinementOptions {
  int max_rounds = 6;        ///< refinement rounds at most (0: off)
  UntangleOptions untangle;  ///< the untangling on each refined mesh
};

/// The faces whose edges a round splits: `faces` grown by `rings` vertex rings. Ascending. \pre rings >= 0.
std::vector<int> grow_faces(const Mesh& mesh, const std::vector<int>& faces, int rings);
/// Every edge of the listed faces, ascending and without repeats. \pre faces index mesh.
std::vector<int> edges_of_faces(const Mesh& mesh, const std::vector<int>& faces);

/// What the refinement did (the report's fold_refinement).
struct FoldRefinementReport {
  int rounds = 0;       ///< rounds run, kept or not
  int kept_rounds = 0;  ///< rounds whose refined map was kept
  int split_edges = 0, added_faces = 0;
  int non_positive_before = 0, non_positive_after = 0;
  int untangle_iterations = 0;  ///< ε rounds and polish steps of the untangling on the kept refined meshes
  /// Its price E_F: the change of ½‖X̃ − ∇φ̃‖² (6.1.1) by the untangling of the refined maps (the refinement alone
  /// leaves it unchanged).
  double energy = 0;
  double seconds = 0;
};

struct FoldRefinement {
  FoldRefinementReport report;
  /// The kept result (mesh null when no round was kept): the refined triangulation (the coarse vertices first, then
  /// the midpoints of `split`, pairs of vertices of the mesh they were split on), the field and the map on it.
  std::shared_ptr<const Mesh> mesh;
  std::vector<std::array<int, 2>> split;
  FrameField field;
  Parameterization map;
};

/// Refines around the non-positive triangles of `map` (param/seams.h) and untangles, as described above. The kept
/// map's untangling record names faces of the refined mesh (stuck_faces, unresolved_faces) and its final counts.
/// \pre field and map belong to mesh and map.subspace is filled (parameterize()). Deterministic.
/// \throw NumericalError if a factorization fails.
FoldRefinement refine_folds(const Mesh& mesh, const FrameField& field, const Parameterization& map,
                            const FoldRefinementOptions& options, ProgressSink& progress);

}  // namespace quadcover
