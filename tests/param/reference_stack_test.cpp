// The product's cover-based code (param/, cover/) against the real-surface reference implementations of thesis
// Chapter 1 (calculus/hodge, calculus/div_curl, topology/homology, topology/harmonic_basis): with a matching ≡ 0
// the covering is four copies of M and every cover-based quantity is its real-surface counterpart.
//  - Curl removal: parameterize()'s E_D = ‖X̃_C‖² equals Σ ‖(X_C)‖² of the Hodge decompositions (Theorem 1.12) of the
//    two scaled frame vectors, on closed meshes and with boundary (v = 0 on boundary edges in both).
//  - Integration: integrate_on_disk (1.12 on the cover's cut disk) equals topology/integrate on the same cut mesh
//    (up to the constant of the start corner).
//  - Periods: the cover's period matrix P_ij = ⟨H_i, Σ_j⟩ (6.3.2) on the free paths of a closed surface is, for
//    each of Re and Im, the Gram matrix of the harmonic fields with unit jumps across an integral homology basis;
//    the reference harmonic basis of topology/harmonic_basis (1.2.6) is that of another integral basis, so the two
//    Gram matrices are congruent by a unimodular matrix: equal determinants.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

#include "calculus/gradient.h"
#include "calculus/hodge.h"
#include "cover/field_helpers.h"
#include "param/harmonic_correction.h"
#include "param/parameterize.h"
#include "param/period_matrix.h"
#include "support/test_meshes.h"
#include "topology/cut_graph.h"
#include "topology/harmonic_basis.h"
#include "topology/homology.h"
#include "topology/integrate.h"

namespace quadcover {
namespace {

FrameField random_frames_zero_matching(const Mesh& mesh, unsigned seed) {
  FrameField field = testing::random_frame_field(mesh, seed);
  field.matching.setZero();
  return field;
}

TEST(ReferenceStack, CurlRemovalOnTheCoverEqualsTheHodgeCoexactPart) {
  const Mesh meshes[] = {testing::make_torus(14, 7), testing::make_cylinder(12, 5),
                         testing::load_test_mesh("lilium_disk")};
  for (const Mesh& mesh : meshes) {
    const FrameField field = random_frames_zero_matching(mesh, 3);
    ParamOptions o;
    o.relaxation.iterations = 0;
    o.stiffening.max_iterations = 0;
    o.untangle.enabled = false;
    o.alignment.enabled = false;
    o.rounding.strategy = RoundingStrategy::Direct;
    const Parameterization P = parameterize(mesh, field, o);
    const HodgeDecomposer hodge(mesh);
    const double reference = l2_norm_squared(mesh, hodge.decompose(P.scale * field.X).coexact) +
                             l2_norm_squared(mesh, hodge.decompose(P.scale * field.Y).coexact);
    ASSERT_GT(reference, 0);
    EXPECT_NEAR(P.energy_curl, reference, 1e-8 * reference) << mesh.num_faces() << " faces";
  }
}

TEST(ReferenceStack, IntegrationOnTheCutDiskEqualsTheReferenceIntegration) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n;
  for (const Mesh& mesh : {testing::make_torus(12, 6), testing::load_test_mesh("lilium_disk")}) {
    const CoverCut cc = build_cover_cut(mesh, Eigen::VectorXi::Zero(mesh.num_edges()));
    Eigen::VectorXd u0(mesh.num_vertices()), u1(mesh.num_vertices());
    for (int v = 0; v < mesh.num_vertices(); ++v) u0[v] = n(rng), u1[v] = n(rng);
    const VectorField X = gradient(mesh, u0), Y = gradient(mesh, u1);  // curl*-free
    FramePairs Z(mesh.num_faces(), 2);
    Z.col(0) = X;
    Z.col(1) = Y;
    const Eigen::MatrixX3cd product = corner_values(cc, integrate_on_disk(mesh, cc, Z));
    const Eigen::MatrixX3cd reference = integrate_frame(mesh, cc.disk, X, Y);
    const Complex shift = product(0, 0) - reference(0, 0);
    double worst = 0;
    for (int f = 0; f < mesh.num_faces(); ++f)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(product(f, c) - reference(f, c) - shift));
    EXPECT_LT(worst, 1e-9 * (1 + reference.cwiseAbs().maxCoeff()));
  }
}

TEST(ReferenceStack, PeriodMatrixIsCongruentToTheReferenceHarmonicGram) {
  for (const char* name : {"torus", "eight_genus2"}) {
    SCOPED_TRACE(name);
    const Mesh mesh = std::string(name) == "torus" ? testing::make_torus(16, 8) : testing::load_test_mesh(name);
    ASSERT_EQ(mesh.num_boundary_loops(), 0);
    const int g = mesh.genus();
    // Cover side: no branch points, trivial holonomy; 2g complex periods, Re and Im decouple.
    const CoverCut cc = build_cover_cut(mesh, Eigen::VectorXi::Zero(mesh.num_edges()));
    const HarmonicCorrection hc(mesh, cc, std::vector<char>(1, 1));
    const PeriodMatrix pm = period_matrix(mesh, cc, hc, 8);
    const int m = static_cast<int>(pm.paths.size());
    ASSERT_EQ(m, 2 * g);
    EXPECT_LT(pm.P.topRightCorner(m, m).cwiseAbs().maxCoeff(), 1e-9 * pm.P.cwiseAbs().maxCoeff());
    const Eigen::MatrixXd cover_re = pm.P.topLeftCorner(m, m), cover_im = pm.P.bottomRightCorner(m, m);
    // Reference side: harmonic fields with unit periods on the homology basis of a cut graph (Algorithm 1.16).
    const HodgeDecomposer hodge(mesh);
    const HomologyBasis basis = homology_basis(mesh, cut_graph(mesh));
    const std::vector<VectorField> H = harmonic_basis(hodge, basis, sigma_fields(mesh, basis));
    ASSERT_EQ(static_cast<int>(H.size()), 2 * g);
    Eigen::MatrixXd gram(2 * g, 2 * g);
    for (int i = 0; i < 2 * g; ++i)
      for (int j = 0; j < 2 * g; ++j) gram(i, j) = l2_inner(mesh, H[i], H[j]);
    // ⟨H_i, Σ_j⟩ = ⟨H_i, H_j⟩ for harmonic H: both are Gram matrices of integral bases of the harmonic fields
    // (unit jumps across the cover's cut paths / across the reference generators), G_cover = Tᵀ G_ref T with
    // T ∈ GL(2g, Z): equal determinants, for Re and for Im.
    const double d_ref = gram.determinant();
    ASSERT_GT(d_ref, 0);
    EXPECT_NEAR(cover_re.determinant(), d_ref, 1e-6 * d_ref);
    EXPECT_NEAR(cover_im.determinant(), d_ref, 1e-6 * d_ref);
  }
}

}  // namespace
}  // namespace quadcover
