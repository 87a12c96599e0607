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
std::vector<CurveSlot> aligned_curve_slots(const Mesh& mesh, const FramePairs& Z, const std::vector<int>& feature_edges,
                                           double tolerance_degrees);

/// The alignment constraints of one map (which real component of u is fixed where, and to what), built once from the
/// unconstrained solution u0, then solved with any matrix of 𝔏̄'s pattern (e.g. the weighted 𝔏̄_w of local
/// stiffening, param/stiffening.h): the first solve analyses the real system, later ones only refactorize.
/// Holds pointers to mesh, cut, layer and known: they must outlive it.
class AlignedCorrection {
 public:
  AlignedCorrection(const Mesh& mesh, const CoverCut& cut, const Eigen::MatrixX3i& layer,
                    const Eigen::MatrixX3cd& known, const Eigen::VectorXcd& u0, const std::vector<int>& kernel_pins,
                    const std::vector<CurveSlot>& slots, double max_shift, double min_length = 0);
  /// u with L u = b (real form) and the constrained components fixed. 	hrow NumericalError if not definite.
  Eigen::VectorXcd solve(const Eigen::SparseMatrix<Complex>& L, const Eigen::VectorXcd& b);
  /// The curves with their largest deviation from the iso-line measured on u.
  std::vector<AlignedCurve> curves(const Eigen::VectorXcd& u) const;
  /// Lines left free because they close on themselves with another integer.
  int conflicts() const { return conflicts_; }

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
};

/// Solves the harmonic correction 𝔏̄ u = b with the alignment constraints (real form of the Hermitian system), given
/// the corner values `known` = φ̂ + σ, the corner layers of u, and the unconstrained solution u0 (for rounding the
/// iso-line values). `kernel_pins`: one vertex per component with trivial holonomy (𝔏̄ has the constants in its
/// kernel there); its real / imaginary part is pinned to 0 unless a constraint already fixes that part somewhere in
/// the component. Lines whose mean must move by more than `max_shift` grid units, or shorter than `min_length` grid
/// units, are left free. Fills `curves`
/// (deviations measured on the result). \return u.
Eigen::VectorXcd solve_aligned_correction(const Mesh& mesh, const CoverCut& cut, const Eigen::SparseMatrix<Complex>& L,
                                          const Eigen::VectorXcd& b, const Eigen::MatrixX3i& layer,
                                          const Eigen::MatrixX3cd& known, const Eigen::VectorXcd& u0,
                                          const std::vector<int>& kernel_pins, const std::vector<CurveSlot>& slots,
                                          std::vector<AlignedCurve>& curves, int& conflicts, double max_shift,
                                          double min_length = 0);

}  // namespace quadcover
