#pragma once
// Even branch points on integer points over the rotated lattice (thesis 4.2.2). An even branch point q sits at
// D_q / 2 (D_q the translation of the transition around q); it is integral iff D_q ∈ 2Z[i]. With every period in
// (1+i)Z[i], D_q ∈ (1+i)Z[i], and a parity step ±(1±i) of the periods of the paths whose cut edges surround q flips
// whether D_q ∈ 2Z[i]: a linear system over GF(2) (rows: even branch points, columns: paths).
#include <complex>
#include <cstdint>
#include <functional>
#include <vector>

#include "mesh/mesh.h"
#include "param/cover_cut.h"

namespace quadcover {

/// GF(2) solve of A x = r by Gauss-Jordan elimination. Rows of A are bit sets of `ncols` columns (64 per word).
/// x is the solution with every non-pivot column 0. Returns false if the system is inconsistent (x then meets the
/// rows that could be met).
/// \pre every row has ceil(ncols / 64) words (or all rows are empty when ncols is 0); r has one bit per row.
bool solve_gf2(std::vector<std::vector<std::uint64_t>> A, std::vector<char> r, int ncols, std::vector<char>& x);

/// Moves the even branch points of `cut` to integer points by a parity step ±(1±i) of the rounded periods of the
/// paths the GF(2) system selects; of the four steps of a path, the one with the smallest price(j) is taken, where
/// price(j) is evaluated with the step applied to rounded_periods[j].
/// \pre rounded_periods has cut.num_paths() entries in (1+i)Z[i] (rotated lattice).
/// \return the even branch points that stay at half-integer points (empty when the system is consistent).
std::vector<int> fix_even_branch_points(const Mesh& mesh, const CoverCut& cut,
                                        std::vector<std::complex<double>>& rounded_periods,
                                        const std::function<double(int path)>& price);

}  // namespace quadcover
