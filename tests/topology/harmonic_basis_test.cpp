// Harmonic bases from Σ_k (thesis 1.2.6): H_k = Σ_k - ∇u with 𝔏u = -div Σ_k, and H_b for given periods (1.14).
#include "topology/harmonic_basis.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>
#include <string>

#include "calculus/div_curl.h"
#include "common/errors.h"
#include "support/test_meshes.h"
#include "topology/base_sets.h"

namespace quadcover {
namespace {

struct BasisCase {
  std::string mesh;
  int num_base;
};

class HarmonicBasisOnMeshes : public ::testing::TestWithParam<BasisCase> {
 protected:
  void SetUp() override {
    mesh_ = testing::load_test_mesh(GetParam().mesh);
    const auto base = testing::random_interior_vertices(mesh_, GetParam().num_base, 42);
    basis_ = homology_basis(mesh_, cut_graph(mesh_, base));
    sigma_ = sigma_fields(mesh_, basis_);
  }
  // max |div H| relative to max |div Σ|, and max |curl* H| on interior edges relative to max |H|·|e|.
  void expect_harmonic(const VectorField& H, const VectorField& S, const std::string& what) const {
    const Eigen::VectorXd div_h = divergence(mesh_, H), div_s = divergence(mesh_, S);
    EXPECT_LE(div_h.cwiseAbs().maxCoeff(), 1e-9 * div_s.cwiseAbs().maxCoeff()) << what;
    const Eigen::VectorXd c = curl_star(mesh_, H);
    double worst = 0, scale = 0;
    for (int e = 0; e < mesh_.num_edges(); ++e) {
      if (mesh_.is_boundary_edge(e)) continue;
      worst = std::max(worst, std::abs(c[e]));
      scale = std::max(scale, std::abs(H[mesh_.EF()(e, 0)]) * mesh_.edge_lengths()[e]);
    }
    EXPECT_LE(worst, 1e-9 * scale) << what;
  }
  Mesh mesh_;
  HomologyBasis basis_;
  Eigen::SparseMatrix<Complex> sigma_;
};

// Each H_k is div free and curl* free, b_j(H_k) = δ_jk, and it equals the harmonic part of Σ_k computed by the
// full Hodge decomposition (Theorem 1.12): an independent route through 𝔏*.
TEST_P(HarmonicBasisOnMeshes, StandardBasisIsHarmonicWithUnitPeriods) {
  const HodgeDecomposer hodge(mesh_);
  const std::vector<VectorField> H = harmonic_basis(hodge, basis_, sigma_);
  ASSERT_EQ(static_cast<int>(H.size()), basis_.size());
  const int n = basis_.size();
  Eigen::MatrixXd gram(n, n);
  for (int k = 0; k < n; ++k) {
    const VectorField S = sigma_.col(k);
    expect_harmonic(H[k], S, "H_" + std::to_string(k));
    const Eigen::VectorXd b = periods(basis_, H[k]);
    for (int j = 0; j < n; ++j) EXPECT_NEAR(b[j], j == k ? 1.0 : 0.0, 1e-9);
    const VectorField via_hodge = hodge.decompose(S).harmonic;
    EXPECT_LE(std::sqrt(l2_norm_squared(mesh_, via_hodge - H[k])), 1e-8 * std::sqrt(l2_norm_squared(mesh_, H[k])));
    for (int j = 0; j <= k; ++j) gram(j, k) = gram(k, j) = l2_inner(mesh_, H[j], H[k]);
  }
  // A basis: the L² Gram matrix is positive definite.
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram).eigenvalues();
  EXPECT_GT(ev.minCoeff(), 1e-8 * ev.maxCoeff());
}

// (1.14): H_b has the requested periods, is harmonic, and is the combination Σ_k b_k H_k.
TEST_P(HarmonicBasisOnMeshes, FieldWithGivenPeriods) {
  const HodgeDecomposer hodge(mesh_);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unif(-3, 3);
  Eigen::VectorXd b(basis_.size());
  for (int j = 0; j < b.size(); ++j) b[j] = unif(rng);
  const VectorField Hb = harmonic_field_with_periods(hodge, basis_, sigma_, b);
  const Eigen::VectorXd got = periods(basis_, Hb);
  for (int j = 0; j < b.size(); ++j) EXPECT_NEAR(got[j], b[j], 1e-9 * (1 + std::abs(b[j])));
  expect_harmonic(Hb, sigma_field(sigma_, b), "H_b");
  const std::vector<VectorField> H = harmonic_basis(hodge, basis_, sigma_);
  VectorField combo = VectorField::Zero(mesh_.num_faces());
  for (int k = 0; k < b.size(); ++k) combo += b[k] * H[k];
  EXPECT_LE(std::sqrt(l2_norm_squared(mesh_, combo - Hb)), 1e-9 * std::sqrt(l2_norm_squared(mesh_, Hb)));
  EXPECT_THROW(harmonic_field_with_periods(hodge, basis_, sigma_, Eigen::VectorXd::Zero(b.size() + 1)), InputError);
}

INSTANTIATE_TEST_SUITE_P(Meshes, HarmonicBasisOnMeshes,
                         ::testing::Values(BasisCase{"torus_5k", 0}, BasisCase{"eight_genus2", 6},
                                           BasisCase{"3holes_genus3", 0}, BasisCase{"fertility_genus4", 3},
                                           BasisCase{"couplingdown_genus9", 0}, BasisCase{"mech_holes_shark", 2}),
                         [](const ::testing::TestParamInfo<BasisCase>& info) {
                           return info.param.mesh + "_B" + std::to_string(info.param.num_base);
                         });

}  // namespace
}  // namespace quadcover
