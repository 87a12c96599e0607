#pragma once
// Splitting high-index singularities into quarter-index branch points (beyond the thesis, using its relocation
// along paths, 5.2.2). A vertex of cross-field quarter index q (Def. 3.3 times 4) is a cone of angle
// 2π(1 - q/4) of the parameterization; q = 4 (index +1, e.g. the apex of a high-valence bipyramid) asks for angle 0,
// which no quad map realizes without folding, and |q| >= 2 gives degenerate quads (valence 2 or >= 6). The split
// moves the quarters one by one to nearby vertices, so Σ q = 4χ (Poincaré–Hopf) is kept and every singularity
// has |q| = 1 (valence 3 or 5 in the quad mesh).
#include <Eigen/Core>
#include <vector>

#include "field/frame_field.h"
#include "mesh/mesh.h"

namespace quadcover {

/// Where one quarter of index goes: from vertex `from` to vertex `to` along an edge path.
struct QuarterMove {
  int from;
  int to;
  int quarters;  ///< +1 or -1: the sign of the index moved (from's q decreases by it, to's increases)
};

/// The moves that leave no interior vertex with |q| >= min_quarters (>= 2), for the quarter indices q (#V,
/// cross_field_quarter_index). Vertices are treated in index order; a vertex of index q gives all |q| quarters to
/// |q| distinct interior vertices of index 0 that no earlier move chose. From its 1-ring when that has enough of
/// them: evenly spaced in fan order, at the rotation whose targets lie farthest apart, then farthest from the other
/// singularities nearby; else from the nearest rings that have enough, by farthest-point sampling. Deterministic.
/// \pre min_quarters >= 2. \throw std::invalid_argument if quarter_index does not have #V entries.
std::vector<QuarterMove> plan_singularity_split(const Mesh& mesh, const Eigen::VectorXi& quarter_index,
                                                int min_quarters = 2);

/// Applies the moves to `matching` (#E): relocation_changes along relocation_path for each (field/relocation.h,
/// 5.2.2). Returns the number of matching changes made (edges crossed, counted once per move).
/// \pre matching has #E entries; moves from plan_singularity_split. \throw std::invalid_argument as relocation_path.
int apply_quarter_moves(const Mesh& mesh, const std::vector<QuarterMove>& moves, Eigen::VectorXi& matching);

}  // namespace quadcover
