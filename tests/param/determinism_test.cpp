// Speed-related rewrites of the parameterization must not change its result: the two factorizations of
// parameterize() run concurrently (𝔏̄* for the curl removal, 𝔏̄ for the harmonic correction), and the period matrix
// (6.3.2) reads ⟨∇u_a, Σ_b⟩ off sparse right-hand sides.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "field/compute_frame_field.h"
#include "param/parameterize.h"
#include "param/period_matrix.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

using testing::load_test_mesh;

// One thread or all threads: bit-identical maps (each factorization and solve is sequential; only whole tasks run
// side by side). Meshes with branch points, boundary (Dirichlet rows) and a closed genus-2 surface (period matrix).
TEST(ParamDeterminism, SameMapWithOneThread) {
  for (const char* name : {"bunny_3k", "lilium_disk", "eight_genus2"}) {
    const Mesh mesh = load_test_mesh(name);
    const FrameField field = compute_frame_field(mesh);
    const Parameterization all = parameterize(mesh, field);
    Parameterization one;
    {
      tbb::global_control serial(tbb::global_control::max_allowed_parallelism, 1);
      one = parameterize(mesh, field);
    }
    ASSERT_FALSE(all.branch_points.empty()) << name;
    EXPECT_EQ(all.energy_curl, one.energy_curl) << name;
    EXPECT_EQ(all.energy_harmonic, one.energy_harmonic) << name;
    EXPECT_TRUE(all.rounded_periods == one.rounded_periods) << name;
    EXPECT_EQ((all.uv - one.uv).cwiseAbs().maxCoeff(), 0.0) << name;
  }
}

// The sparse right-hand side of a jump field equals the dense one, and the period matrix does not depend on the
// block size of its solves (up to the round-off of the BLAS kernels the solver picks per block width).
TEST(ParamDeterminism, SparseRightHandSideAndBlockSize) {
  const Mesh mesh = load_test_mesh("fertility_genus4");
  const FrameField field = compute_frame_field(mesh);
  const CoverCut cc = build_cover_cut(mesh, field.matching);
  const HarmonicCorrection hc(mesh, cc, std::vector<char>(static_cast<std::size_t>(mesh.num_components()), 0));
  ASSERT_GT(cc.num_paths(), 4);
  for (int j = 0; j < cc.num_paths(); ++j) {
    const SparseJumpField s = unit_jump_field(mesh, cc, j);
    ASSERT_FALSE(s.support.empty());
    FramePairs S = FramePairs::Zero(mesh.num_faces(), 2);
    for (std::size_t k = 0; k < s.support.size(); ++k) S.row(s.support[k]) << s.X[k], s.Y[k];
    const Eigen::VectorXcd dense = hc.rhs(S), sparse = hc.rhs(s.support, s.X, s.Y);
    EXPECT_LE((dense - sparse).cwiseAbs().maxCoeff(), 1e-14 * dense.cwiseAbs().maxCoeff()) << j;
  }
  const PeriodMatrix one = period_matrix(mesh, cc, hc, 1), many = period_matrix(mesh, cc, hc, 64);
  ASSERT_EQ(one.paths, many.paths);
  EXPECT_GT(one.P.diagonal().minCoeff(), 0);
  EXPECT_LE((one.P - many.P).cwiseAbs().maxCoeff(), 1e-12 * one.P.diagonal().maxCoeff());
}

}  // namespace
}  // namespace quadcover
