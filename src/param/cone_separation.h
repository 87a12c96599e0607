#pragma once
// Branch points kept off one lattice point by re-rounding the periods (issue 14 item 3, beyond the thesis). Every
// branch point p sits on the fixed point of the transitions composed around it, z ↦ i^K z + D (4.2): φ(p) =
// D / (1 − i^K) (param/disk_functions.h branch_point_image), and D is a Gaussian-integer combination of the rounded
// periods (param/disk_functions.h complete_translations). Two branch points a few edges apart that the rounding (6.3)
// puts on one point hold the triangles between them at zero area (adjacent ones) or force a fold or a wrong winding
// there, and no untangling in the seamless subspace undoes that. Their offset φ(q) − φ(p), seen along a shortest face
// path from p, is linear in the cut translations; changing one free period by one lattice step moves it by a known
// amount. Steps are taken one at a time, the cheapest by E_H (6.3) among those that lower the number of close pairs on
// one point and move no even branch point off its integer point (param/even_branch_fix.h).
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "param/cover_cut.h"
#include "param/lattice.h"

namespace quadcover {

/// Two branch points to keep off one lattice point.
struct ConePair {
  int p, q;
};

/// φ(q) − φ(p) in the chart of p's first fan face, reached along a shortest path of faces from there to q's first fan
/// face: a linear function of the cut translations T (#E).
class ConePairOffset {
 public:
  /// \pre cut = build_cover_cut(mesh, …); p, q are interior branch points of one component of `cut`.
  ConePairOffset(const Mesh& mesh, const CoverCut& cut, ConePair pair);
  /// The offset for translations T. \pre T has #E entries.
  Complex operator()(const Eigen::VectorXcd& T) const;

 private:
  const Mesh* mesh_;
  const CoverCut* cut_;
  ConePair pair_;
  std::vector<FanCrossing> path_;  ///< faces from p's first fan face to q's
};

/// The separation's inputs: the cut, the translations of ∫X̂ on the cut edges, the periods b_j and the paths that may
/// change (the free ones of the rounding, one lattice step at a time), and E_H of a choice of rounded periods.
struct SeparationProblem {
  const Mesh& mesh;
  const CoverCut& cut;
  const Eigen::VectorXcd& continuous;  ///< #E: c_e of ∫X̂ (param/disk_functions.h cut_translations)
  const std::vector<Complex>& periods;
  std::vector<char> free_path;  ///< per path
  Lattice lattice;
  std::function<double(const std::vector<Complex>& rounded)> energy;
};

/// What the separation did.
struct SeparationResult {
  std::vector<ConePair> coincident;  ///< the close pairs on one point before
  int left = 0;                      ///< close pairs on one point after (a step may put another pair on one point)
  int steps = 0;                     ///< lattice steps taken
  std::vector<ConePair> set_apart;   ///< pairs of `coincident` on different points after
};

/// The pairs of close_branch_points(kWatchedRings) that `rounded` puts on one point. \pre as separate_cones.
std::vector<ConePair> coincident_cones(const SeparationProblem& problem, const std::vector<Complex>& rounded);

/// The pairs of interior branch points of `cut` within `rings` rings of each other, p < q, in vertex order.
/// \pre cut = build_cover_cut(mesh, …); rings >= 0.
std::vector<ConePair> close_branch_points(const Mesh& mesh, const CoverCut& cut, int rings);
/// Branch points this close are kept apart by separate_cones.
inline constexpr int kWatchedRings = 4;

/// Changes `rounded` (the rounded periods) so that no pair of close_branch_points(kWatchedRings) shares a point: one
/// lattice step of one free period at a time, the step with the smallest E_H among those that lower the number of
/// pairs on one point and leave no more even branch points off the integer points, while there is one. Pairs no
/// step sets apart keep their point.
/// \pre rounded and periods have cut.num_paths() entries.
SeparationResult separate_cones(const SeparationProblem& problem, std::vector<Complex>& rounded);

/// The cut translations of a rounding: continuous + the completed jumps rounded − periods on the paths' edges.
/// \pre as separate_cones.
Eigen::VectorXcd rounded_translations(const SeparationProblem& problem, const std::vector<Complex>& rounded);

}  // namespace quadcover
