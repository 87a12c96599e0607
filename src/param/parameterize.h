#pragma once
// QuadCover parameterization (thesis Chapters 2 and 4, Algorithm 2.1 on the covering M̃):
//  1. cut M through B = branch points ∪ boundary and gauge the frames on the cut disk (4.2),
//  2. curl removal on the covering: 𝔏̄* v = -curl* Z̃, X̂ = Z - J∇v (4.1, (2.1), (3.3), (3.8)),
//  3. integrate X̂ over the cut disk (1.12) and read the complex periods b_j of the symmetric paths,
//  4. round the periods to the lattice (4.2.2; fix-up of even branch points on the rotated lattice),
//  5. harmonic correction H̃_d = Σ̃_d - (Σ̃_d)_P with the conforming 𝔏̄ (branch rows removed) ((1.14) on M̃),
//  6. φ = ∫(X̂ + H̃_d): per-corner complex coordinates in grid units (then relaxation, local stiffening and the
//     untangling of the remaining flipped or collapsed triangles).
#include <memory>

#include "common/progress.h"
#include "field/feature_alignment.h"
#include "param/alignment.h"
#include "param/cone_separation.h"
#include "param/density.h"
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
  /// The quad edge length h: given, from a quad count, or the default (param/density.h).
  DensityOptions density;
  /// Rounding of the periods to the lattice (6.3): the period matrix P_ij = ⟨H_i, Σ_j⟩ of the harmonic fields of
  /// the symmetric paths is computed column by column (6.3.2) and E_H = ½ dᵀ P d is minimized by the strategy.
  /// Direct skips P (nearest lattice point, 4.2.2).
  RoundingOptions rounding;
  /// Keep branch points within kWatchedRings of each other off one lattice point: the rounded periods get the
  /// cheapest lattice steps that set them apart (param/cone_separation.h); not when the curves' integers are rounded
  /// with the periods (alignment.round_with_periods). Otherwise the pairs on one point are only listed
  /// (ParamDiagnostics::Rounding::coincident_cones).
  bool separate_close_cones = false;
  /// Move even branch points to integer points by adjusting one period each (rotated lattice only).
  bool fix_even_branch_points = true;
  /// Sharp features (with the boundaries, the curves of the alignment below).
  FeatureOptions features;
  /// Boundary and sharp feature curves on integer iso-lines (beyond the thesis; param/alignment.h).
  CurveAlignmentOptions alignment;
  /// ARAP relaxation of the final map (beyond the thesis, param/relaxation.h).
  RelaxationOptions relaxation;
  /// Local stiffening of the final solve against flipped triangles (beyond the thesis, param/stiffening.h); it
  /// follows the relaxed targets when relaxation ran.
  StiffeningOptions stiffening;
  /// Untangling and injective polish of the final map when it has a flipped or collapsed triangle (beyond the
  /// thesis, param/untangle.h): seams, periods, branch points and curve constraints stay fixed.
  UntangleOptions untangle;
};

/// Seamless QuadCover parameterization of `mesh` guided by `field`: SolvedMap(…).finish().
/// \pre mesh is a valid triangle mesh; field has #F frames (non-zero) and a #E matching.
/// \throw InputError on size mismatches, NumericalError if a factorization fails.
Parameterization parameterize(const Mesh& mesh, const FrameField& field, const ParamOptions& options = {},
                              ProgressSink& progress = null_progress());

/// parameterize() in two parts: steps 1-5 in the constructor, which fix E_D (energy_curl) and E_H
/// (energy_harmonic); the relaxation, stiffening, untangling and step 6 in finish(). A caller that compares maps by
/// E_D + E_H (optimize/optimize_field.h, keep better) finishes only the one it keeps.
class SolvedMap {
 public:
  /// The mesh, field and progress sink must outlive the object. \pre and \throw as parameterize().
  SolvedMap(const Mesh& mesh, const FrameField& field, const ParamOptions& options = {},
            ProgressSink& progress = null_progress());
  ~SolvedMap();
  SolvedMap(SolvedMap&&) noexcept;
  SolvedMap& operator=(SolvedMap&&) noexcept;

  /// ‖X̃_C‖² of the map, as in the finished Parameterization. \pre not finished
  double energy_curl() const;
  /// E_H of the map, as in the finished Parameterization. \pre not finished
  double energy_harmonic() const;
  /// h_sym of the cut and the field's scale (grid units per unit of the unscaled field), as in the finished
  /// Parameterization. \pre not finished
  int h_sym() const;
  double scale() const;  ///< \pre not finished
  /// The rest of parameterize(); the object is spent. \throw InputError if called twice, NumericalError if a
  /// factorization fails.
  Parameterization finish() &&;

  struct State;

 private:
  std::unique_ptr<State> state_;
};

}  // namespace quadcover
