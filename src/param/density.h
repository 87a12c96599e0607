#pragma once
// The density of the map: the quad edge length h that one grid unit stands for (ParamOptions::density).
#include "field/frame_field.h"
#include "mesh/mesh.h"

namespace quadcover {

struct DensityOptions {
  /// Target quad edge length h in model units (> 0 to use). One grid unit = h along the (RMS-normalized) field.
  double edge_length = 0;
  /// Target number of quads N (> 0 to use, when edge_length is 0): h = sqrt(area / N).
  int target_quads = 0;
  /// Default density when neither is given: h = default_edge_factor × mean mesh edge length (≈ #F / 9 quads on
  /// a regular mesh), or finer so that there are at least min_quads_per_branch_point quads per branch point of the
  /// field (h ≤ sqrt(area / (min_quads_per_branch_point · #branch points)); 0 = no such bound). Branch points sit on
  /// integer points: a grid with a few quads per cone must fold (BENCHMARKS.md, "Default density").
  double default_edge_factor = 2.0;
  double min_quads_per_branch_point = 30.0;
};

/// The quad edge length h that `options` asks for on `mesh` with a field of `branch_points` branch points.
/// \throw InputError if the edge length or the quad count is negative.
double target_edge_length(const Mesh& mesh, const DensityOptions& options, int branch_points = 0);

/// Fixes the default density of `options` (neither edge_length nor target_quads given) to an explicit edge_length
/// from the branch point count of `field`, so that every later stage (Algorithm 6.1's E_H, keep-better's comparison
/// of two fields) works at one scale. Explicit densities are left as they are.
/// \pre field belongs to mesh. \throw InputError as target_edge_length.
void fix_default_density(const Mesh& mesh, const FrameField& field, DensityOptions& options);

}  // namespace quadcover
