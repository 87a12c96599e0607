// Cutting along the cut graph of Algorithm 1.16 leaves a topological disk (thesis 1.3): one piece, one boundary
// loop and χ = 1, on closed meshes of genus 0-9, meshes with boundaries, and with several (random) base vertices.
#include "topology/cut_mesh.h"

#include <gtest/gtest.h>

#include <string>

#include "common/errors.h"
#include "support/test_meshes.h"
#include "topology/base_sets.h"
#include "topology/cut_graph.h"

namespace quadcover {
namespace {

// Checks the disk property and the bookkeeping of a cut mesh against a direct recount.
void expect_disk(const Mesh& mesh, const Eigen::VectorXi& cut, const CutMesh& cm) {
  EXPECT_EQ(cm.num_pieces, 1);
  EXPECT_EQ(cm.boundary_loops.size(), 1u);
  EXPECT_EQ(cm.euler_characteristic(mesh), 1);
  // Every corner has a cut-vertex lying over its own vertex.
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int cv = cm.corner_vertex(f, k);
      ASSERT_GE(cv, 0);
      EXPECT_EQ(cm.original_vertex[cv], mesh.F()(f, k));
    }
  // The boundary loop runs over both sides of every interior cut edge and over every mesh boundary edge.
  int expected_length = 0;
  for (int e = 0; e < mesh.num_edges(); ++e) expected_length += mesh.is_boundary_edge(e) ? 1 : (cut[e] ? 2 : 0);
  std::size_t total = 0;
  for (const auto& loop : cm.boundary_loops) {
    total += loop.size();
    for (std::size_t i = 0; i < loop.size(); ++i) {  // consecutive half-edges share their cut-vertex
      const auto& h = loop[i];
      const auto& next = loop[(i + 1) % loop.size()];
      EXPECT_EQ(cm.corner_vertex(h.face, (h.corner + 1) % 3), cm.corner_vertex(next.face, next.corner));
      const int e = mesh.FE()(h.face, (h.corner + 2) % 3);
      EXPECT_TRUE(mesh.is_boundary_edge(e) || cut[e]);
    }
  }
  EXPECT_EQ(static_cast<int>(total), expected_length);
}

using testing::BaseSetCase;

class CutMeshOnMeshes : public ::testing::TestWithParam<BaseSetCase> {};

TEST_P(CutMeshOnMeshes, CutGraphCutsToADisk) {
  const Mesh mesh = testing::load_test_mesh(GetParam().mesh);
  const auto base = testing::random_interior_vertices(mesh, GetParam().num_base, GetParam().seed);
  const CutGraph g = cut_graph(mesh, base);
  const CutMesh cm = cut_mesh(mesh, g.cut);
  expect_disk(mesh, g.cut, cm);
  // Every base vertex lies on the disk boundary (it is split or on the cut), so branch points are cut.
  std::vector<int> copies(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (const auto& h : cm.boundary_loops[0]) ++copies[mesh.F()(h.face, h.corner)];
  for (const int b : base) EXPECT_GE(copies[b], 1) << "base vertex " << b;
}

INSTANTIATE_TEST_SUITE_P(
    Meshes, CutMeshOnMeshes,
    ::testing::Values(BaseSetCase{"torus_5k", 0, 1}, BaseSetCase{"torus_5k", 3, 11}, BaseSetCase{"eight_genus2", 0, 1},
                      BaseSetCase{"eight_genus2", 9, 12}, BaseSetCase{"3holes_genus3", 0, 1},
                      BaseSetCase{"3holes_genus3", 4, 13}, BaseSetCase{"fertility_genus4", 0, 1},
                      BaseSetCase{"fertility_genus4", 8, 14}, BaseSetCase{"couplingdown_genus9", 0, 1},
                      BaseSetCase{"couplingdown_genus9", 6, 15}, BaseSetCase{"bunny_3k", 2, 16},
                      BaseSetCase{"bunny_3k", 10, 17}, BaseSetCase{"spot", 8, 18}, BaseSetCase{"cow", 3, 19},
                      BaseSetCase{"fandisk", 5, 20}, BaseSetCase{"lilium_disk", 0, 1},
                      BaseSetCase{"lilium_disk", 6, 21}, BaseSetCase{"camelhead_boundary", 0, 1},
                      BaseSetCase{"camelhead_boundary", 5, 22}, BaseSetCase{"mech_holes_shark", 0, 1},
                      BaseSetCase{"mech_holes_shark", 4, 23}, BaseSetCase{"bunny_20k_holes", 0, 1},
                      BaseSetCase{"bunny_20k_holes", 7, 24}),
    testing::base_set_case_name);

// Many random base sets on a small genus-2 mesh.
TEST(CutMesh, RandomBaseSetsAlwaysGiveADisk) {
  const Mesh mesh = testing::load_test_mesh("eight_genus2");
  for (unsigned seed = 100; seed < 130; ++seed) {
    const auto base = testing::random_interior_vertices(mesh, 1 + static_cast<int>(seed % 17), seed);
    const CutGraph g = cut_graph(mesh, base);
    expect_disk(mesh, g.cut, cut_mesh(mesh, g.cut));
  }
}

// Without cuts a closed sphere stays a sphere (χ = 2, no boundary); an uncut torus is not a disk (χ = 0).
TEST(CutMesh, UncutSurfacesKeepTheirTopology) {
  const Mesh sphere = testing::make_ellipsoid(2);
  const CutMesh s = cut_mesh(sphere, Eigen::VectorXi::Zero(sphere.num_edges()));
  EXPECT_EQ(s.euler_characteristic(sphere), 2);
  EXPECT_TRUE(s.boundary_loops.empty());
  EXPECT_EQ(s.num_vertices(), sphere.num_vertices());
  const Mesh torus = testing::make_torus(10, 6);
  EXPECT_EQ(cut_mesh(torus, Eigen::VectorXi::Zero(torus.num_edges())).euler_characteristic(torus), 0);
  // Cutting everything separates all faces: f pieces, each a triangle with its own three cut-vertices.
  const CutMesh all = cut_mesh(torus, Eigen::VectorXi::Ones(torus.num_edges()));
  EXPECT_EQ(all.num_pieces, torus.num_faces());
  EXPECT_EQ(all.num_vertices(), 3 * torus.num_faces());
  EXPECT_EQ(all.boundary_loops.size(), static_cast<std::size_t>(torus.num_faces()));
}

// Several components are cut independently: a torus and a cylinder in one mesh give two disks.
TEST(CutMesh, EveryComponentBecomesADisk) {
  const Mesh both = testing::make_torus_and_cylinder();
  ASSERT_EQ(both.num_components(), 2);
  const CutGraph g = cut_graph(both);
  EXPECT_EQ(g.paths.size(), 3u);  // 2g = 2 loops on the torus, b - 1 = 1 path on the cylinder
  const CutMesh cm = cut_mesh(both, g.cut);
  EXPECT_EQ(cm.num_pieces, 2);
  EXPECT_EQ(cm.boundary_loops.size(), 2u);
  EXPECT_EQ(cm.euler_characteristic(both), 2);
  for (const auto& loop : cm.boundary_loops)  // one loop per piece
    for (const auto& h : loop) EXPECT_EQ(cm.face_piece[h.face], cm.face_piece[loop[0].face]);
}

TEST(CutMesh, RejectsWrongSize) {
  const Mesh torus = testing::make_torus(8, 6);
  EXPECT_THROW(cut_mesh(torus, Eigen::VectorXi::Zero(3)), InputError);
}

}  // namespace
}  // namespace quadcover
