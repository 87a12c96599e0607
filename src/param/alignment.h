#pragma once
// Alignment of boundary and feature curves to integer iso-lines (beyond the thesis). Where the guiding frame is
// fixed along a boundary or sharp feature curve (field/feature_alignment.h), the edge is parallel to one frame
// vector, so one coordinate of φ should be constant along it; the final solve makes it a constant integer.
//
// The constraints act on the covering-continuous potential u of the harmonic correction only (φ = φ̂ + σ - u), so
// the seams stay exact: a curve edge in face f with coordinate a (0: φ⁰, 1: φ¹) asks Re(i^{-a} φ_f) = n at both
// endpoints, i.e. one real component of u_p. Curve slots sharing a cut-vertex and coordinate form one iso-line,
// whose integer n is the rounded mean of the unconstrained solution along it.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <limits>
#include <vector>

#include "calculus/sparse_cholesky.h"
#include "param/cover_cut.h"
#include "param/disk_functions.h"
#include "param/parameterization.h"

namespace quadcover {

/// One aligned curve (a run of curve edges sharing an iso-line): edges, coordinate, integer value n, and the largest
/// |coordinate - n| over its vertices after the solve (grid units).
using AlignedCurve = Parameterization::Curve;

/// A curve edge e whose frame in face f is parallel (within the tolerance) to e.
struct CurveSlot {
  int edge, face, coordinate;
};

/// Boundary edges and the given feature edges whose gauged frame Z (#F by 2) is aligned with them within
/// `tolerance_degrees`: the edge is parallel to Z(f, 1 - a) and the coordinate a is constant along it.
/// \pre Z is #F by 2; feature_edges are edges of mesh.
std::vector<CurveSlot> aligned_curve_slots(const Mesh& mesh, const FramePairs& Z, const std::vector<int>& feature_edges,
                                           double tolerance_degrees);

/// Which iso-lines are worth pinning, in grid units measured on the unconstrained map u0. Pinning a line moves it
/// by its shift and straightens it by its spread; lines beyond either limit, or shorter than min_length, stay free.
struct CurveLimits {
  double max_shift = 0.35;  ///< |mean coordinate − the line's integer| (through a branch point: its integer)
  double min_length = 0;    ///< length of the line
  double max_spread = std::numeric_limits<double>::infinity();  ///< max − min of the coordinate along the line
};

/// Which curves are put on integer iso-lines (ParamOptions::alignment): boundary edges and the sharp edges of the
/// features, where the field is aligned with them.
struct CurveAlignmentOptions {
  bool enabled = true;
  /// A curve edge counts as aligned when a frame vector is within this angle of it.
  double tolerance_degrees = 2.0;
  /// Straightening a line wigglier than max_spread bends the map around it (BENCHMARKS.md, "Option defaults");
  /// pinning crease fragments shorter than min_length costs distortion and folds for no visible gain.
  CurveLimits limits{.max_shift = 0.35, .min_length = 3.0, .max_spread = 1.0};
};

/// The alignment constraints of one map (which real component of u is fixed where, and to what), built once from the
/// unconstrained solution u0, then solved with any matrix of 𝔏̄'s pattern (e.g. the weighted 𝔏̄_w of local
/// stiffening, param/stiffening.h): the first solve analyses the real system, later ones only refactorize.
/// Holds pointers to mesh, cut, layer and known: they must outlive it.
class AlignedCorrection {
 public:
  /// \pre cut = build_cover_cut(mesh, …); layer, known #F by 3; u0 #V; slots from aligned_curve_slots.
  AlignedCorrection(const Mesh& mesh, const CoverCut& cut, const Eigen::MatrixX3i& layer,
                    const Eigen::MatrixX3cd& known, const Eigen::VectorXcd& u0, const std::vector<int>& kernel_pins,
                    const std::vector<CurveSlot>& slots, const CurveLimits& limits);
  /// u with L u = b (real form) and the constrained components fixed. \throw NumericalError if not definite.
  /// refactorize = false reuses the factor of the previous call (L must be the same matrix; only b changes).
  Eigen::VectorXcd solve(const Eigen::SparseMatrix<Complex>& L, const Eigen::VectorXcd& b, bool refactorize = true);
  /// The curves with their largest deviation from the iso-line measured on u. \pre u has #V entries.
  std::vector<AlignedCurve> curves(const Eigen::VectorXcd& u) const;
  /// Lines left free because they close on themselves with another integer. \pre none
  int conflicts() const { return conflicts_; }
  /// 2·#V flags (x_p at p, y_p at #V + p) of the components of u that the constraints fix. \pre none
  const std::vector<char>& fixed_components() const { return fixed_; }

 private:
  const Mesh* mesh_;
  const CoverCut* cut_;
  const Eigen::MatrixX3i* layer_;
  const Eigen::MatrixX3cd* known_;
  std::vector<CurveSlot> slots_;
  std::vector<AlignedCurve> curves_;
  int conflicts_ = 0;
  std::vector<int> curve_of_;   ///< per slot: its curve
  std::vector<double> n_of_;    ///< per slot: the integer its coordinate must equal
  std::vector<char> fixed_;     ///< 2·#V: x then y components of u that are fixed
  Eigen::VectorXd value_;       ///< their values
  SparseCholesky<double> chol_;
  bool factored_ = false;
};

}  // namespace quadcover
