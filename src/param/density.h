#pragma once
// The density of the map: the quad edge length h that one grid unit stands for (ParamOptions::density).
#include <vector>

#include "field/frame_field.h"
#include "mesh/mesh.h"

namespace quadcover {

/// A closed crease loop round a hole through the part whose turning side the field leaves free (field/crease_loops.h):
/// the default density resolves it as it resolves a boundary loop.
struct HoleRim {
  int lowest_vertex = -1;
  double length = 0;
};

struct DensityOptions {
  /// Target quad edge length h in model units (> 0 to use). One grid unit = h along the (RMS-normalized) field.
  double edge_length = 0;
  /// Target number of quads N (> 0 to use, when edge_length is 0): h = sqrt(area / N), then rescaled in
  /// parameterize() so that the free map has N expected faces (param/face_count.h).
  int target_quads = 0;
  /// Default density when neither is given: h = default_edge_factor × mean mesh edge length (≈ #F / 9 quads on
  /// a regular mesh), or finer so that there are at least min_quads_per_branch_point quads per branch point of the
  /// field (h ≤ sqrt(area / (min_quads_per_branch_point · #branch points)); 0 = no such bound). Branch points sit on
  /// integer points: a grid with a few quads per cone must fold (BENCHMARKS.md, "Default density").
  double default_edge_factor = 2.0;
  double min_quads_per_branch_point = 30.0;
  /// The default density is also made finer so that every boundary loop is at least min_loop_grid_units quad edges
  /// around (its length / h): a shorter hole has no ring of quads and the quad mesh closes over it (issue 14 item 4,
  /// 15 item 3). Only for the loops that reach it within max_loop_quads_factor times the quads and at most one quad
  /// per input triangle (the memory stays that of the input's resolution); 0 = off.
  double min_loop_grid_units = 4.0;
  double max_loop_quads_factor = 16.0;
  /// Hole rims held to the same minimum as the boundary loops (set by the pipeline with the rims it frees).
  std::vector<HoleRim> hole_rims;
  /// Per connected component, in the order of their lowest vertex numbers, how many times finer than h its quads
  /// are: component c is meshed at edge length h / component_density[c]. Empty: 1 everywhere. Set by
  /// fix_component_density.
  std::vector<double> component_density;
  /// edge_length is the job's own density made explicit by a validity retry (pipeline/validity_retries.h), not a
  /// length the user gave: the components still get their own density.
  bool edge_length_from_default = false;
};

/// The boundary loop or hole rim that made the default density finer (DensityOptions::min_loop_grid_units).
struct LoopResolution {
  int loop = -1;            ///< index into mesh.boundary_loops() (or hole_rims), -1 when no loop made it finer
  bool rim = false;         ///< the loop is DensityOptions::hole_rims[loop]
  int lowest_vertex = -1;   ///< that loop's lowest vertex number (0-based)
  double length = 0;        ///< its length in model units
  double quads_factor = 1;  ///< the quads of the finer density over those of the coarser one (1: not finer)
  double edge_length = 0;   ///< the coarser default h that quads_factor is relative to
};

/// The loop of `mesh` that needs the finest density within the bounds of DensityOptions::min_loop_grid_units from the
/// default edge length `h`, and its factor in quads. \pre h > 0
LoopResolution loop_resolution(const Mesh& mesh, const DensityOptions& options, double h);

/// The quad edge length h that `options` asks for on `mesh` with a field of `branch_points` branch points.
/// \throw InputError if the edge length or the quad count is negative.
double target_edge_length(const Mesh& mesh, const DensityOptions& options, int branch_points = 0);

/// Fixes the default density of `options` (neither edge_length nor target_quads given) to an explicit edge_length
/// from the branch point count of `field`, so that every later stage (Algorithm 6.1's E_H, keep-better's comparison
/// of two fields) works at one scale. Explicit densities are left as they are.
/// \return the loop that made it finer (LoopResolution::loop -1: none, or an explicit density).
/// \pre field belongs to mesh. \throw InputError as target_edge_length.
LoopResolution fix_default_density(const Mesh& mesh, const FrameField& field, DensityOptions& options);

/// Sets options.component_density for the edge length h on a mesh of several components: one h for all leaves a
/// small component few quads for its branch points, and its map folds (BENCHMARKS.md, "Components of very different
/// sizes"). A component with branch points gets at least min_quads_per_branch_point quads per branch point of
/// `field` (its area / (h / ρ)² ≥ min · its branch points), at most one quad per triangle of it; ρ ≥ 1. Empty when
/// every ρ is 1. \return whether any ρ > 1. \pre h > 0, field belongs to mesh.
bool fix_component_density(const Mesh& mesh, const FrameField& field, double h, DensityOptions& options);

/// Per face, the density factor of its component (DensityOptions::component_density, Parameterization's copy; 1 when
/// empty). \pre none
Eigen::VectorXd face_density(const Mesh& mesh, const std::vector<double>& component_density);
/// Per vertex, the density factor of its component (as face_density). \pre none
Eigen::VectorXd vertex_density(const Mesh& mesh, const std::vector<double>& component_density);

}  // namespace quadcover
