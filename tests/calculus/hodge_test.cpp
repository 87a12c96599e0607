// Hodge decomposition (Theorem 1.12, (1.8)-(1.10)) on real meshes of genus 0-4, with and without boundary:
// orthogonality, the defining kernels, recovery of known potentials, and dim 𝓗 = 2g (+ b - 1 with boundary).
#include "calculus/hodge.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <vector>

#include "calculus/div_curl.h"
#include "calculus/gradient.h"
#include "calculus/stiffness.h"
#include "calculus_test_util.h"

namespace quadcover {
namespace {

using testing::cached_mesh;
using testing::random_field;
using testing::random_vector;

const Complex kQuarterTurn{0, 1};  // J, the rotation by 90° in the tangent plane

class HodgeOnRealMeshes : public ::testing::TestWithParam<const char*> {};

void expect_valid_decomposition(const Mesh& mesh, const VectorField& X, const HodgeParts& h) {
  const double norm2 = l2_norm_squared(mesh, X);
  EXPECT_LT(l2_norm_squared(mesh, h.exact + h.coexact + h.harmonic - X), 1e-24 * norm2);
  // Mutual L² orthogonality of 𝒫, 𝒞, 𝓗.
  EXPECT_LT(std::abs(l2_inner(mesh, h.exact, h.coexact)), 1e-10 * norm2);
  EXPECT_LT(std::abs(l2_inner(mesh, h.exact, h.harmonic)), 1e-10 * norm2);
  EXPECT_LT(std::abs(l2_inner(mesh, h.coexact, h.harmonic)), 1e-10 * norm2);
  // The parts are what they claim: ∇u, J∇v, and 𝓗 = ker div ∩ ker curl* (interior edges).
  EXPECT_LT(l2_norm_squared(mesh, h.exact - gradient(mesh, h.potential)), 1e-24 * norm2);
  EXPECT_LT(l2_norm_squared(mesh, h.coexact - kQuarterTurn * nonconforming_gradient(mesh, h.copotential)),
            1e-24 * norm2);
  const double scale = std::sqrt(norm2 / mesh.total_area()) * mesh.mean_edge_length();  // typical |⟨X, e⟩|
  EXPECT_LT(divergence(mesh, h.harmonic).lpNorm<Eigen::Infinity>(), 1e-9 * scale);
  const Eigen::VectorXd cs = curl_star(mesh, h.harmonic);
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (mesh.is_boundary_edge(e)) {
      ASSERT_EQ(h.copotential[e], 0.0) << "Dirichlet co-potential on boundary edge " << e;
    } else {
      ASSERT_LT(std::abs(cs[e]), 1e-9 * scale) << "curl* of the harmonic part at edge " << e;
    }
  }
  // (1.10) per component.
  Eigen::VectorXd iu = Eigen::VectorXd::Zero(mesh.num_components()), iv = iu;
  const Eigen::VectorXd av = vertex_areas(mesh), ae = edge_areas(mesh);
  for (int p = 0; p < mesh.num_vertices(); ++p) iu[mesh.vertex_component()[p]] += av[p] * h.potential[p];
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int f = mesh.EF()(e, 0) >= 0 ? mesh.EF()(e, 0) : mesh.EF()(e, 1);
    iv[mesh.face_component()[f]] += ae[e] * h.copotential[e];
  }
  const double potential_scale = h.potential.lpNorm<Eigen::Infinity>() * mesh.total_area();
  const double copotential_scale = h.copotential.lpNorm<Eigen::Infinity>() * mesh.total_area();
  for (int c = 0; c < mesh.num_components(); ++c) {
    EXPECT_LT(std::abs(iu[c]), 1e-12 * potential_scale) << "component " << c;
    if (mesh.components()[c].boundary_loops == 0) {
      EXPECT_LT(std::abs(iv[c]), 1e-12 * copotential_scale) << "component " << c;
    }
  }
}

TEST_P(HodgeOnRealMeshes, PartsAreOrthogonalAndSumToField) {
  const Mesh& mesh = cached_mesh(GetParam());
  const HodgeDecomposer hodge(mesh);
  const VectorField X = random_field(mesh, 71);
  const HodgeParts h = hodge.decompose(X);
  expect_valid_decomposition(mesh, X, h);
  // A random field has a substantial curl and potential part.
  EXPECT_GT(l2_norm_squared(mesh, h.exact), 1e-3 * l2_norm_squared(mesh, X));
  EXPECT_GT(l2_norm_squared(mesh, h.coexact), 1e-3 * l2_norm_squared(mesh, X));
}

// X = ∇u0 + J∇v0 + H with known u0, v0 (v0 = 0 on boundary edges) and H harmonic is decomposed into exactly those.
TEST_P(HodgeOnRealMeshes, RecoversKnownPotentials) {
  const Mesh& mesh = cached_mesh(GetParam());
  const HodgeDecomposer hodge(mesh);
  Eigen::VectorXd u0 = random_vector(mesh.num_vertices(), 72), v0 = random_vector(mesh.num_edges(), 73);
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (mesh.is_boundary_edge(e)) v0[e] = 0;
  const VectorField H = hodge.decompose(random_field(mesh, 74)).harmonic;
  const VectorField X = gradient(mesh, u0) + kQuarterTurn * nonconforming_gradient(mesh, v0) + H;
  const HodgeParts h = hodge.decompose(X);
  expect_valid_decomposition(mesh, X, h);
  // Expected potentials after (1.10): subtract the area-weighted mean (single-component meshes).
  ASSERT_EQ(mesh.num_components(), 1);
  const Eigen::VectorXd av = vertex_areas(mesh), ae = edge_areas(mesh);
  u0.array() -= av.dot(u0) / av.sum();
  if (mesh.num_boundary_loops() == 0) v0.array() -= ae.dot(v0) / ae.sum();
  EXPECT_LT((h.potential - u0).lpNorm<Eigen::Infinity>(), 1e-9);
  EXPECT_LT((h.copotential - v0).lpNorm<Eigen::Infinity>(), 1e-9);
  EXPECT_LT(l2_norm_squared(mesh, h.harmonic - H), 1e-20 * l2_norm_squared(mesh, X));
}

// The solves satisfy (1.8) and (1.9) row by row.
TEST_P(HodgeOnRealMeshes, PotentialsSolveTheLinearSystems) {
  const Mesh& mesh = cached_mesh(GetParam());
  const HodgeDecomposer hodge(mesh);
  const VectorField X = random_field(mesh, 75);
  const Eigen::VectorXd div = divergence(mesh, X), cs = curl_star(mesh, X);
  const Eigen::VectorXd r = conforming_stiffness(mesh) * hodge.exact_potential(X) + div;
  EXPECT_LT(r.norm(), 1e-10 * div.norm());
  const Eigen::VectorXd rs = nonconforming_stiffness(mesh) * hodge.coexact_potential(X) + cs;
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (!mesh.is_boundary_edge(e)) {
      ASSERT_LT(std::abs(rs[e]), 1e-10 * cs.norm()) << "edge " << e;
    }
  EXPECT_EQ(&hodge.mesh(), &mesh);
}

// Every available factorization backend gives the same decomposition (CHOLMOD vs Eigen when both are built).
TEST_P(HodgeOnRealMeshes, BackendsAgree) {
  const Mesh& mesh = cached_mesh(GetParam());
  const VectorField X = random_field(mesh, 76);
  const HodgeParts reference = HodgeDecomposer(mesh, {CholeskyBackend::Eigen}).decompose(X);
  std::vector<CholeskyBackend> others{CholeskyBackend::Automatic};
  if (SparseCholesky<double>::cholmod_available()) others.push_back(CholeskyBackend::Cholmod);
  for (const CholeskyBackend backend : others) {
    const HodgeParts h = HodgeDecomposer(mesh, {backend}).decompose(X);
    EXPECT_LT((h.potential - reference.potential).lpNorm<Eigen::Infinity>(), 1e-10);
    EXPECT_LT((h.copotential - reference.copotential).lpNorm<Eigen::Infinity>(), 1e-10);
    EXPECT_LT(l2_norm_squared(mesh, h.harmonic - reference.harmonic), 1e-20 * l2_norm_squared(mesh, X));
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, HodgeOnRealMeshes, ::testing::ValuesIn(testing::kCalculusMeshes));

/// Numerical rank of the harmonic parts of `count` random fields: eigenvalues of their L² Gram matrix above
/// 1e-10 · max ‖X_i‖² (exact zeros are ~1e-25 relative, genuine directions ~1e-3).
int harmonic_rank(const Mesh& mesh, int count) {
  const HodgeDecomposer hodge(mesh);
  std::vector<VectorField> H;
  double max_norm2 = 0;
  for (int i = 0; i < count; ++i) {
    const VectorField X = random_field(mesh, 100 + 13 * static_cast<unsigned>(i));
    max_norm2 = std::max(max_norm2, l2_norm_squared(mesh, X));
    H.push_back(hodge.decompose(X).harmonic);
  }
  Eigen::MatrixXd gram(count, count);
  for (int i = 0; i < count; ++i)
    for (int j = 0; j < count; ++j) gram(i, j) = l2_inner(mesh, H[i], H[j]);
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram).eigenvalues();
  return static_cast<int>((ev.array() > 1e-10 * max_norm2).count());
}

struct GenusCase {
  const char* name;
  int expected_dimension;  ///< 2g + b - 1 (2g when closed)
};
class HarmonicDimension : public ::testing::TestWithParam<GenusCase> {};

// dim 𝓗 = 2g on closed surfaces (Theorem 1.12): 2g + 3 random fields have harmonic parts spanning exactly 2g
// dimensions; with b boundary loops (Dirichlet co-potential) it is 2g + b - 1.
TEST_P(HarmonicDimension, HarmonicPartsSpanTheHomology) {
  const GenusCase c = GetParam();
  const Mesh& mesh = cached_mesh(c.name);
  const int g = mesh.genus(), b = mesh.num_boundary_loops();
  ASSERT_EQ(b == 0 ? 2 * g : 2 * g + b - 1, c.expected_dimension);
  EXPECT_EQ(harmonic_rank(mesh, c.expected_dimension + 3), c.expected_dimension);
}

INSTANTIATE_TEST_SUITE_P(Meshes, HarmonicDimension,
                         ::testing::Values(GenusCase{"bunny_3k", 0}, GenusCase{"torus_5k", 2},
                                           GenusCase{"eight_genus2", 4}, GenusCase{"3holes_genus3", 6},
                                           GenusCase{"fertility_genus4", 8}, GenusCase{"lilium_disk", 0},
                                           GenusCase{"mech_holes_shark", 3}),
                         [](const auto& info) { return std::string(info.param.name); });

// Several components: the kernel is removed and (1.10) holds on each component separately (a closed torus, a
// closed ellipsoid and an open grid in one mesh); dim 𝓗 = 2 + 0 + 0.
TEST(Hodge, SeveralComponents) {
  const Mesh parts[] = {testing::make_torus(24, 12), testing::make_ellipsoid(3, 1.0, 0.6, 0.4), testing::make_grid(8)};
  Eigen::MatrixX3d V(0, 3);
  Eigen::MatrixX3i F(0, 3);
  for (const Mesh& m : parts) {
    Eigen::MatrixX3d V2(V.rows() + m.num_vertices(), 3);
    V2 << V, m.V().rowwise() + Eigen::RowVector3d(3.0 * static_cast<double>(&m - parts), 0, 0);
    Eigen::MatrixX3i F2(F.rows() + m.num_faces(), 3);
    F2 << F, m.F().array() + static_cast<int>(V.rows());
    V = V2;
    F = F2;
  }
  const Mesh mesh = Mesh::from_triangles(V, F);
  ASSERT_EQ(mesh.num_components(), 3);
  const HodgeDecomposer hodge(mesh);
  const VectorField X = random_field(mesh, 81);
  expect_valid_decomposition(mesh, X, hodge.decompose(X));
  EXPECT_EQ(harmonic_rank(mesh, 5), 2);
}

}  // namespace
}  // namespace quadcover
