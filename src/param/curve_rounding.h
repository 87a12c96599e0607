#pragma once
// Rounding of the periods together with the integers of the aligned curves (beyond the thesis: 6.3 with the curve
// constraints of param/alignment.h). The period-matrix rounding weighs E_H of the free harmonic correction and the
// curves are pinned afterwards, so a curve whose branch points or closing the rounding put on two integers, or whose
// free map wiggles, is left free. Here the quadratic form is that of the constrained correction,
//   E(x, n) = min { ‖Σ̃_d − ∇u‖² : u puts every chosen line k on its iso-line n_k },
// in the real coordinates x of the free periods and one integer n_k per line, plus a penalty on the lines' closing
// and branch-point conditions (param/alignment.h AlignedLines); one search (RoundingOptions) then rounds both, so
// that the cones go where the curves can be straight.
#include <Eigen/Core>
#include <vector>

#include "param/alignment.h"
#include "param/harmonic_correction.h"
#include "param/lattice.h"
#include "param/period_rounding.h"

namespace quadcover {

/// The chosen lines, their integers and the rounded periods. Inactive when no line qualifies or the dense responses
/// would not fit (`max_response_bytes`): the caller then rounds with the period matrix alone.
struct CurveRounding {
  bool active = false;
  std::vector<char> lines;         ///< per line of the AlignedLines: put on an integer iso-line with these periods
  Eigen::VectorXd line_values;     ///< per line: its integer (chosen lines)
  std::vector<int> paths;          ///< the rounded (free) paths
  std::vector<Complex> periods;    ///< their rounded periods
  int variables = 0;               ///< real variables of the rounding: 2·#paths + #lines
  int conditions = 0, conditions_met = 0;  ///< closing and branch-point conditions of the chosen lines
  double energy_direct = 0;        ///< E at the direct rounding of the periods with the best continuous n, rounded
  double energy_rounded = 0;       ///< E at the result
  RoundingResult search;
};

struct CurveRoundingInputs {
  const CoverCut& cut;
  const HarmonicCorrection& correction;
  const AlignedLines& aligned;  ///< the lines of the aligned curves
  const Eigen::MatrixX3cd& known_free;  ///< per corner, φ̂ (the integral before the period rounding)
  const std::vector<Complex>& periods, &direct;  ///< per path: the periods and their direct rounding
  double edge_length = 1;               ///< h in model units (line lengths in grid units)
  Eigen::VectorXd face_density = {};    ///< per face, ρ of its component (param/density.h face_density; empty: 1)
  std::vector<char> left_free = {};     ///< per line: not to be pinned (empty: none)
};

/// Lines worth pinning: usable (param/alignment.h), at least `min_length` grid units long (h / ρ a unit on a component
/// meshed ρ times finer) and not in.left_free.
/// Rounds as above. \throw NumericalError if a factorization fails.
CurveRounding round_with_curves(const Mesh& mesh, const CurveRoundingInputs& in, Lattice lattice,
                                const RoundingOptions& options, double min_length,
                                double max_response_bytes = 512e6);

}  // namespace quadcover
