// The GF(2) solver of the even branch point fix-up (thesis 4.2.2) against direct evaluation of A x over GF(2), and
// the fix-up inside parameterize(): every even branch point of the rotated-lattice map lands on an integer point.
#include "param/even_branch_fix.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "cover/field_helpers.h"
#include "param/disk_functions.h"
#include "param/lattice.h"
#include "param/parameterize.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

using Rows = std::vector<std::vector<std::uint64_t>>;

bool bit(const std::vector<std::uint64_t>& row, int j) { return (row[j / 64] >> (j % 64)) & 1; }

// (A x)_q over GF(2), computed directly.
std::vector<char> multiply(const Rows& A, const std::vector<char>& x) {
  std::vector<char> r(A.size(), 0);
  for (std::size_t q = 0; q < A.size(); ++q)
    for (std::size_t j = 0; j < x.size(); ++j) r[q] ^= x[j] && bit(A[q], static_cast<int>(j));
  return r;
}

TEST(SolveGf2, ConsistentSystemsAreSolvedExactly) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const int ncols = 1 + static_cast<int>(rng() % 150), nrows = 1 + static_cast<int>(rng() % 60);
    const std::size_t words = (static_cast<std::size_t>(ncols) + 63) / 64;
    Rows A(static_cast<std::size_t>(nrows), std::vector<std::uint64_t>(words, 0));
    for (auto& row : A)
      for (int j = 0; j < ncols; ++j)
        if (rng() % 4 == 0) row[j / 64] |= std::uint64_t{1} << (j % 64);
    std::vector<char> x0(static_cast<std::size_t>(ncols));
    for (char& b : x0) b = static_cast<char>(rng() % 2);
    const std::vector<char> r = multiply(A, x0);  // consistent by construction
    std::vector<char> x;
    ASSERT_TRUE(solve_gf2(A, r, ncols, x)) << trial;
    ASSERT_EQ(x.size(), static_cast<std::size_t>(ncols));
    EXPECT_EQ(multiply(A, x), r) << trial;
  }
}

TEST(SolveGf2, InconsistentSystemIsReported) {
  // x0 = 1, x0 = 0 (the same row twice with different right-hand sides) and an empty row with r = 1.
  const Rows A = {{1}, {1}};
  std::vector<char> x;
  EXPECT_FALSE(solve_gf2(A, {1, 0}, 3, x));
  EXPECT_FALSE(solve_gf2({{0}}, {1}, 2, x));
  EXPECT_TRUE(solve_gf2({{0}}, {0}, 2, x));
  EXPECT_EQ(x, std::vector<char>(2, 0));
}

// Twice the position of an even branch point is D_q (the translation of the transition around it): it is integral
// iff D_q/2 ∈ Z[i]. After the fix-up every even one of the rotated-lattice map is, unless reported unfixed.
TEST(EvenBranchFix, ParameterizeLeavesNoEvenBranchPointAtHalfIntegers) {
  int evens = 0;
  for (unsigned seed : {1u, 2u}) {
    const Mesh mesh = testing::make_torus(24, 12);
    const FrameField field = testing::random_cross_field(mesh, seed);  // many close cones, even ones among them
    ParamOptions o;
    o.relaxation.iterations = 0;
    o.stiffening.max_iterations = 0;
    o.untangle.enabled = false;
    o.alignment.enabled = false;
    const Parameterization P = parameterize(mesh, field, o);
    const CoverCut cc = build_cover_cut(mesh, field.matching);
    const Eigen::VectorXcd c = cut_translations(mesh, cc, P.uv);
    for (int q = 0; q < mesh.num_vertices(); ++q) {
      if (!cc.branch[q] || ((cc.quarter_index[q] % 4) + 4) % 4 != 2) continue;
      ++evens;
      const bool unfixed = std::count(P.diagnostics.unfixed_even_branch_points.begin(), P.diagnostics.unfixed_even_branch_points.end(), q);
      if (!unfixed) {
        EXPECT_LT(distance_to_gaussian_integers(0.5 * transition_around(mesh, cc, c, q).second), 1e-6);
      }
    }
  }
  EXPECT_GT(evens, 0);
}

}  // namespace
}  // namespace quadcover
