#pragma once
// QuadCover parameterization (thesis Chapters 2 and 4, Algorithm 2.1 on the covering M̃):
//  1. cut M through B = branch points ∪ boundary and gauge the frames on the cut disk (4.2),
//  2. curl removal on the covering: 𝔏̄* v = -curl* Z̃, X̂ = Z - J∇v (4.1, (2.1), (3.3), (3.8)),
//  3. integrate X̂ over the cut disk (1.12) and read the complex periods b_j of the symmetric paths,
//  4. round the periods to the lattice (4.2.2; fix-up of even branch points on the rotated lattice),
//  5. harmonic correction H̃_d = Σ̃_d - (Σ̃_d)_P with the conforming 𝔏̄ (branch rows removed) ((1.14) on M̃),
//  6. φ = ∫(X̂ + H̃_d): per-corner complex coordinates in grid units (then relaxation, local stiffening and the
//     untangling of the remaining flipped or collapsed triangles).
#include "common/progress.h"
#include "field/feature_alignment.h"
#include "param/lattice.h"
#include "param/parameterization.h"
#include "param/period_rounding.h"
#include "param/relaxation.h"
#include "param/stiffening.h"
#include "param/untangle.h"

namespace quadcover {

struct ParamOptions {
  /// Rounding lattice of the periods (4.2.2). Default: rotated, (1+i)Z[i].
  Lattice lattice = Lattice::Rotated;
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
  /// Rounding of the periods to the lattice (6.3): the period matrix P_ij = ⟨H_i, Σ_j⟩ of the harmonic fields of
  /// the symmetric paths is computed column by column (6.3.2) and E_H = ½ dᵀ P d is minimized by the strategy.
  /// Direct skips P (nearest lattice point, 4.2.2).
  RoundingOptions rounding;
  /// Move even branch points to integer points by adjusting one period each (rotated lattice only).
  bool fix_even_branch_points = true;
  /// Put boundary and sharp feature curves on integer iso-lines where the field is aligned with them (beyond the
  /// thesis; param/alignment.h). Curves: boundary edges and the sharp edges of `features`.
  bool align_curves = true;
  FeatureOptions features;
  /// A curve edge counts as aligned when a frame vector is within this angle of it.
  double align_tolerance_degrees = 2.0;
  /// A curve is put on its nearest integer line (through a branch point on it: that point's line) only if that
  /// moves it by at most this many grid units on average; farther ones stay free and their deviation is reported.
  double align_max_shift = 0.35;
  /// ... and only if its coordinate varies along it by at most this many grid units in the unconstrained map.
  /// Straightening a wigglier line bends the map around it (BENCHMARKS.md, "Option defaults").
  double align_max_spread = 1.0;
  /// Curves shorter than this many grid units (quad edge lengths) stay free: pinning short crease fragments costs
  /// distortion and folds for no visible gain.
  double align_min_length = 3.0;
  /// ARAP relaxation of the final map (beyond the thesis, param/relaxation.h).
  RelaxationOptions relaxation;
  /// Local stiffening of the final solve against flipped triangles (beyond the thesis, param/stiffening.h); it
  /// follows the relaxed targets when relaxation ran.
  StiffeningOptions stiffening;
  /// Untangling and injective polish of the final map when it has a flipped or collapsed triangle (beyond the
  /// thesis, param/untangle.h): seams, periods, branch points and curve constraints stay fixed.
  UntangleOptions untangle;
};

/// The quad edge length h that `options` asks for on `mesh` with a field of `branch_points` branch points (see
/// ParamOptions). \throw InputError if negative.
double target_edge_length(const Mesh& mesh, const ParamOptions& options, int branch_points = 0);

/// Fixes the default density of `options` (neither edge_length nor target_quads given) to an explicit edge_length
/// from the branch point count of `field`, so that every later stage (Algorithm 6.1's E_H, keep-better's comparison
/// of two fields) works at one scale. Explicit densities are left as they are.
/// \pre field belongs to mesh. \throw InputError as target_edge_length.
void fix_default_density(const Mesh& mesh, const FrameField& field, ParamOptions& options);

/// Seamless QuadCover parameterization of `mesh` guided by `field`.
/// \pre mesh is a valid triangle mesh; field has #F frames (non-zero) and a #E matching.
/// \throw InputError on size mismatches, NumericalError if a factorization fails.
Parameterization parameterize(const Mesh& mesh, const FrameField& field, const ParamOptions& options = {},
                              ProgressSink& progress = null_progress());

}  // namespace quadcover
