// Matchings, curvature (3.4) and indices (Def. 1.18, 3.2, 3.3) on real closed meshes of genus 0-4.
#include "field/indices.h"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "field/curvature_frames.h"
#include "field/matching.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

Eigen::VectorXcd random_directions(int n, unsigned seed) {
  std::mt19937 rng(seed);
  Eigen::VectorXcd X(n);
  for (int t = 0; t < n; ++t) X[t] = std::polar(1.0, 2 * std::numbers::pi * (rng() / 4294967296.0));
  return X;
}

struct IndexCase {
  std::string mesh;
  int genus;
};

class ClosedMeshes : public ::testing::TestWithParam<IndexCase> {};

// Checks every index identity for one field: Poincaré–Hopf for the cross-field and vector-field indices,
// Σ ind(m) = 0 (each edge is crossed once in each direction by the loops of its two endpoints), and the exact
// split ind^cross = ind(m) + ind(X) at every vertex; in particular the two frame indices agree modulo 1.
void check_indices(const Mesh& mesh, const FrameField& field) {
  const int chi = mesh.euler_characteristic();
  const Eigen::VectorXi cross = cross_field_quarter_index(mesh, field);
  const Eigen::VectorXi match = matching_quarter_index(mesh, field.matching);
  const Eigen::VectorXi vec = vector_field_index(mesh, field.X);
  EXPECT_EQ(cross.sum(), 4 * chi);
  EXPECT_EQ(vec.sum(), chi);
  EXPECT_EQ(match.sum(), 0);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    ASSERT_EQ(cross[v], match[v] + 4 * vec[v]) << "vertex " << v;
    ASSERT_EQ(((cross[v] - match[v]) % 4 + 4) % 4, 0);
  }
  int branch_quarters = 0;
  for (const auto& b : branch_points(mesh, field)) {
    EXPECT_NE(b.quarter_index % 4, 0);
    EXPECT_EQ(b.quarter_index, cross[b.vertex]);
    branch_quarters += b.quarter_index;
  }
  // Regular vertices contribute multiples of 4, so the branch points carry 4χ modulo 4.
  EXPECT_EQ(((branch_quarters - 4 * chi) % 4 + 4) % 4, 0);
}

TEST_P(ClosedMeshes, CurvatureFieldIndices) {
  const Mesh mesh = testing::load_test_mesh(GetParam().mesh);
  ASSERT_EQ(mesh.genus(), GetParam().genus);
  ASSERT_EQ(mesh.num_boundary_loops(), 0);
  const CurvatureFrames frames = principal_curvature_frames(mesh);
  const FrameField field = cross_field_with_straightest_matching(mesh, frames.direction);
  const Eigen::VectorXd theta = field_curvature(mesh, field);
  EXPECT_LE(theta.cwiseAbs().maxCoeff(), std::numbers::pi / 4 + 1e-12);  // (5.1) makes |θ| <= π/4
  check_indices(mesh, field);
}

TEST_P(ClosedMeshes, QuarterIndexOfTheBranchPointsIsTheCrossFieldIndexOffTheRegularVertices) {
  const Mesh mesh = testing::load_test_mesh(GetParam().mesh);
  const FrameField field = cross_field_with_straightest_matching(mesh, principal_curvature_frames(mesh).direction);
  const Eigen::VectorXi cross = cross_field_quarter_index(mesh, field);
  const std::vector<BranchPoint> points = branch_points(mesh, field);
  const Eigen::VectorXi q = quarter_index_of(mesh.num_vertices(), points);
  ASSERT_EQ(q.size(), mesh.num_vertices());
  EXPECT_EQ(static_cast<std::size_t>((q.array() != 0).count()), points.size());
  for (int v = 0; v < mesh.num_vertices(); ++v) EXPECT_EQ(q[v], cross[v] % 4 != 0 ? cross[v] : 0) << v;
}

TEST_P(ClosedMeshes, RandomFieldIndices) {
  const Mesh mesh = testing::load_test_mesh(GetParam().mesh);
  const FrameField field = cross_field_with_straightest_matching(mesh, random_directions(mesh.num_faces(), 7));
  check_indices(mesh, field);
  EXPECT_GT(branch_points(mesh, field).size(), 10u);  // a random field is full of singularities
}

// Any matching, not only (5.1), and non-orthogonal frames (indices use the orthogonalized frame (X,Y)^⊥):
// Poincaré–Hopf still holds and the two indices still agree modulo 4 quarters.
TEST_P(ClosedMeshes, ArbitraryMatchingAndGeneralFrames) {
  const Mesh mesh = testing::load_test_mesh(GetParam().mesh);
  std::mt19937 rng(11);
  FrameField field;
  field.X = random_directions(mesh.num_faces(), 3);
  field.Y = Complex(0, 1) * field.X;
  for (int t = 0; t < mesh.num_faces(); ++t) field.Y[t] = 1.7 * field.Y[t] + 0.4 * field.X[t];  // skewed frames
  field.matching.resize(mesh.num_edges());
  for (int e = 0; e < mesh.num_edges(); ++e) field.matching[e] = static_cast<int>(rng() % 9) - 4;
  const Eigen::VectorXi cross = cross_field_quarter_index(mesh, field);
  EXPECT_EQ(cross.sum(), 4 * mesh.euler_characteristic());
  EXPECT_EQ(matching_quarter_index(mesh, field.matching).sum(), 0);
  const Eigen::VectorXi match = matching_quarter_index(mesh, field.matching);
  for (int v = 0; v < mesh.num_vertices(); ++v) ASSERT_EQ(((cross[v] - match[v]) % 4 + 4) % 4, 0) << v;
  // Adding full turns (multiples of 4) to the matching changes neither θ nor the cross-field index.
  FrameField turned = field;
  for (int e = 0; e < mesh.num_edges(); e += 3) turned.matching[e] += 4 * (e % 2 ? 1 : -1);
  EXPECT_EQ(cross_field_quarter_index(mesh, turned), cross);
}

INSTANTIATE_TEST_SUITE_P(Genus, ClosedMeshes,
                         ::testing::Values(IndexCase{"bunny_3k", 0}, IndexCase{"torus_5k", 1},
                                           IndexCase{"eight_genus2", 2}, IndexCase{"3holes_genus3", 3},
                                           IndexCase{"fertility_genus4", 4}),
                         [](const auto& info) { return info.param.mesh; });

// A field that is parallel in the plane has no singularities and zero curvature; rotating the representative
// vector of one face by a quarter turn changes the matching on its edges but neither θ nor any index.
TEST(Indices, RepresentativeChoiceDoesNotMatter) {
  const Mesh mesh = testing::make_grid(8);
  Eigen::VectorXcd X(mesh.num_faces());
  for (int t = 0; t < mesh.num_faces(); ++t) X[t] = mesh.to_local(t, Eigen::Vector3d(0.6, 0.8, 0));
  FrameField field = cross_field_with_straightest_matching(mesh, X);
  EXPECT_EQ(field.matching.cwiseAbs().sum(), 0);
  EXPECT_LT(field_curvature(mesh, field).cwiseAbs().maxCoeff(), 1e-12);
  const int t = 40;
  X[t] *= Complex(0, 1);
  const FrameField turned = cross_field_with_straightest_matching(mesh, X);
  EXPECT_EQ(turned.matching.cwiseAbs().sum(), 3);  // the three interior edges of face 40
  EXPECT_LT(field_curvature(mesh, turned).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(cross_field_quarter_index(mesh, turned).cwiseAbs().sum(), 0);
  EXPECT_EQ(matching_quarter_index(mesh, turned.matching).cwiseAbs().sum(), 0);
}

// A single index-¼ singularity built by hand: four faces around a flat valence-4 vertex, the cross turning by
// π/8 per face; the matching closing the loop is one quarter turn. Both indices are +¼ there.
TEST(Indices, QuarterSingularityOnFlatFan) {
  Eigen::MatrixX3d V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0;
  Eigen::MatrixX3i F(4, 3);
  F << 0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1;
  const Mesh mesh = Mesh::from_triangles(V, F);
  Eigen::VectorXcd X(4);
  for (int t = 0; t < 4; ++t) {
    const double a = std::numbers::pi / 8 * t;
    X[t] = mesh.to_local(t, Eigen::Vector3d(std::cos(a), std::sin(a), 0));
  }
  const FrameField field = cross_field_with_straightest_matching(mesh, X);
  EXPECT_EQ(cross_field_quarter_index(mesh, field)[0], 1);
  EXPECT_EQ(matching_quarter_index(mesh, field.matching)[0], 1);
  const auto bps = branch_points(mesh, field);
  ASSERT_EQ(bps.size(), 1u);
  EXPECT_EQ(bps[0].vertex, 0);
  EXPECT_EQ(bps[0].quarter_index, 1);
}

}  // namespace
}  // namespace quadcover
