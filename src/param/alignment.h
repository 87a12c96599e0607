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
#include <optional>
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
  /// Round the periods and the lines' integers together (param/curve_rounding.h): the lines of at least
  /// limits.min_length grid units are then pinned whatever their shift and spread on the free map. The job frees the
  /// lines through the wrong windings of that map, and falls back to the period-matrix rounding when the map is still
  /// less valid. Off by default: it costs distortion and time where it gains nothing (BENCHMARKS.md, "Curves freed
  /// at wrong windings").
  bool round_with_periods = false;
  /// With round_with_periods: the lines through any of these vertices (ascending) are not rounded with the periods
  /// and stay free. The job frees the lines around the spots where the map with every line pinned was not valid.
  std::vector<int> free_line_vertices;
};

/// The lines of the aligned curves (connected sets of slots fixing one component of u at shared vertices), with what
/// the rounding with the curves (param/curve_rounding.h) needs (beyond the thesis): the components each line fixes
/// and their values for given per-corner values `known` of φ at u = 0 and per-line integers n, and the conditions
/// under which a line can be one iso-line: closing on itself (a boundary loop, a crease through a cut) with its own
/// integer, and passing its branch points, whose positions the periods set, at that integer. Each condition is a
/// residual in grid units, linear in (known, n) and 0 when it holds.
class AlignedLines {
 public:
  /// \pre cut = build_cover_cut(mesh, …); layer #F by 3 (the correction's layers); slots from aligned_curve_slots.
  AlignedLines(const Mesh& mesh, const CoverCut& cut, const Eigen::MatrixX3i& layer, std::vector<CurveSlot> slots);
  /// The lines (connected sets of relations, numbered by their lowest slot as AlignedCorrection numbers its curves).
  int num_lines() const { return num_lines_; }  ///< \pre none
  /// Per line: whether it fixes a component of u somewhere (not all its slot ends at branch points) and closes on
  /// itself with the same orientation (σ) wherever it does. \pre none
  const std::vector<char>& line_usable() const { return usable_; }
  /// Per line: the length of its edges, each in model units times `face_weight` of its slot's face (empty: 1).
  /// \pre face_weight is empty or #F.
  std::vector<double> line_lengths(const Eigen::VectorXd& face_weight = {}) const;
  /// Per line: whether an endpoint of one of its edges is flagged in `vertex_flags`. \pre vertex_flags is #V.
  std::vector<char> lines_touching(const std::vector<char>& vertex_flags) const;
  /// Residuals of the lines in `lines` only: their closing relations, and n_k − (the integer of each branch point on
  /// line k) for the per-line integers n. Linear in (known, n). \pre known #F by 3; lines and n per line.
  Eigen::VectorXd line_residuals(const Eigen::MatrixX3cd& known, const Eigen::VectorXd& n,
                                 const std::vector<char>& lines) const;
  /// 2·#V flags: the components of u the lines in `lines` fix. \pre lines has num_lines() flags.
  std::vector<char> fixed_components(const std::vector<char>& lines) const;
  /// The values of those components (2·#V, 0 elsewhere) for per-corner values `known` and per-line integers n:
  /// ± (coordinate − n_slot) with n_slot = σ n_line + τ along the line. Linear in (known, n). \pre as line_residuals.
  Eigen::VectorXd fixed_values(const Eigen::MatrixX3cd& known, const Eigen::VectorXd& n,
                               const std::vector<char>& lines) const;

 private:
  /// A relation n_to = σ n_from + τ between the integers of two slots (τ from `known` at two corners of one vertex).
  struct Relation {
    int from, to, sigma;
    int face_from, corner_from, face_to, corner_to;
  };
  /// A branch point at an end of a slot: its coordinate gives the line its integer.
  struct Anchor {
    int slot, face, corner;
  };
  const Mesh* mesh_;
  std::vector<CurveSlot> slots_;
  std::vector<int> order_;                 ///< slots in breadth-first order over the relations, line by line
  std::vector<int> parent_;                ///< per slot: the relation that reached it, or -1 (the root of its line)
  std::vector<int> sigma_of_;              ///< per slot: n_slot = σ n_root + τ
  std::vector<Relation> relations_;        ///< every relation, tree ones included
  std::vector<int> closing_;               ///< relations off the tree whose σ agrees: one residual each
  std::vector<std::vector<Anchor>> anchors_;  ///< per line with a branch point on it (line_anchor_)
  /// One end of a slot off the branch points: the real component (index x_p: p, y_p: #V + p) it fixes, and its sign.
  struct Use {
    int slot, face, corner, index, sign;
  };
  std::vector<Use> uses_;
  std::vector<int> line_of_;  ///< per slot
  int num_lines_ = 0;
  std::vector<char> usable_;
  std::vector<int> line_anchor_;  ///< per anchor line (anchors_), its line
  double coordinate(int slot, int face, int corner, const Eigen::MatrixX3cd& known) const;
  std::vector<double> tau_along(const Eigen::MatrixX3cd& known) const;  ///< τ per slot (tree order)
  double relation_tau(const Relation& rel, const Eigen::MatrixX3cd& known) const;
  /// The line's integer that the branch point of `a` asks for: σ (coordinate − τ) there.
  double root_value(const Anchor& a, const std::vector<double>& tau_of, const Eigen::MatrixX3cd& known) const;
  void trace_lines(const Mesh& mesh, const CoverCut& cut, const std::vector<std::vector<int>>& at_slot);
};

/// Lines and integers the rounding chose with the periods (param/curve_rounding.h), numbered as AlignedLines numbers
/// them: they replace AlignedCorrection's rounded means and limits (lines with branch points at two integers stay free).
struct GivenLines {
  std::vector<char> lines;  ///< per line
  Eigen::VectorXd values;   ///< per line: its integer
  std::vector<char> freed;  ///< per line: left free by CurveAlignmentOptions::free_line_vertices (or empty)
};

/// Fixes, on each trivial-holonomy component of `kernel_pins`, the components of u there that nothing in `fixed`
/// fixes on that component (the constant kernel, x and y apart), with value 0. \pre fixed, value 2·#V.
void pin_kernel(const Mesh& mesh, const std::vector<int>& kernel_pins, std::vector<char>& fixed,
                Eigen::VectorXd& value);

/// 𝔏̄ u = b in the real form of the Hermitian system with some real components of u held at given values (x_p at p,
/// y_p at #V + p): the curve constraints of AlignedCorrection and of the rounding with the curves (param/curve_rounding.h).
/// The first factorize() analyses the reduced real system, later ones only refactorize (same pattern).
class ConstrainedSolve {
 public:
  /// \pre fixed has 2·#V flags.
  explicit ConstrainedSolve(std::vector<char> fixed);
  /// Factors the free rows and columns of L. \throw NumericalError if not definite.
  void factorize(const Eigen::SparseMatrix<Complex>& L);
  /// u for each column of B (#V rows) with the fixed components at the matching column of `values` (2·#V rows).
  /// \pre factorize(L) ran with this L. \throw NumericalError if the solve fails.
  Eigen::MatrixXcd solve(const Eigen::SparseMatrix<Complex>& L, const Eigen::MatrixXcd& B,
                         const Eigen::MatrixXd& values) const;

 private:
  std::vector<char> fixed_;
  std::vector<int> free_id_;  ///< per real component: its row in the reduced system, or -1
  int free_count_ = 0;
  SparseCholesky<double> chol_;
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
                    const std::vector<CurveSlot>& slots, const CurveLimits& limits, const GivenLines* given = nullptr);
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
  std::optional<ConstrainedSolve> solver_;  ///< built at the first solve
  bool factored_ = false;
};

}  // namespace quadcover
