// check_boundary_loops on real remeshes: every non-quad face at a boundary is counted for its loop, the loop's length
// is its edges' length over h, and the reason names the cause: a hole too short for a ring of quads on a plate,
// a boundary line that closes with another integer on lilium_disk (gone with the curves rounded with the periods).
#include "pipeline/boundary_loop_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "pipeline/remesh_mesh.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

/// make_grid(40) without its four middle cells: a square hole of side 0.05 in the unit square.
Mesh plate_with_small_hole() {
  const Mesh grid = testing::make_grid(40);
  std::vector<Eigen::Vector3i> kept;
  for (int f = 0; f < grid.num_faces(); ++f) {
    const Eigen::Vector3d c =
        (grid.V().row(grid.F()(f, 0)) + grid.V().row(grid.F()(f, 1)) + grid.V().row(grid.F()(f, 2))) / 3;
    if (std::abs(c.x() - 0.5) > 0.025 || std::abs(c.y() - 0.5) > 0.025) kept.push_back(grid.F().row(f));
  }
  Eigen::MatrixX3i F(static_cast<int>(kept.size()), 3);
  for (int f = 0; f < F.rows(); ++f) F.row(f) = kept[f];
  return Mesh::from_triangles(grid.V(), F);
}

int non_quads(const QuadMesh& q) { return q.num_faces() - q.num_quads(); }

/// The loop's record is consistent with the input mesh: the loop through its first vertex has no lower vertex and
/// as many edges. Loops are numbered in the order of their first vertices.
void expect_loop_matches_mesh(const Mesh& mesh, const std::vector<BoundaryLoopCheck>& checks, std::size_t k) {
  const BoundaryLoopCheck& c = checks[k];
  EXPECT_EQ(c.loop, static_cast<int>(k) + 1);
  if (k > 0) {
    EXPECT_LT(checks[k - 1].first_vertex, c.first_vertex);
  }
  int found = 0;
  for (std::size_t l = 0; l < mesh.boundary_loops().size(); ++l) {
    const std::vector<int>& vertices = mesh.boundary_loops()[l];
    if (std::find(vertices.begin(), vertices.end(), c.first_vertex - 1) == vertices.end()) continue;
    ++found;
    EXPECT_EQ(c.first_vertex, *std::min_element(vertices.begin(), vertices.end()) + 1);
    EXPECT_EQ(c.edges, static_cast<int>(mesh.boundary_loop_edges()[l].size()));
  }
  EXPECT_EQ(found, 1);
  EXPECT_LE(c.enforced_lines, c.lines);
  EXPECT_EQ(c.reason.empty(), c.non_quads == 0 && !c.closed_over);
  const int v = c.first_vertex - 1;
  EXPECT_EQ(c.at, mesh.V().row(v).transpose());
}

TEST(BoundaryLoopCheck, AHoleShorterThanARingOfQuadsIsNamedWithItsLength) {
  const Mesh plate = plate_with_small_hole();
  ASSERT_EQ(plate.num_boundary_loops(), 2);
  PipelineOptions options;
  options.param.density.edge_length = 0.1;  // the hole is 0.2 around: 2 grid units
  options.extraction.quadrangulate_boundary = false;  // the clipped polygons are what is named
  const RemeshJob job = remesh_mesh(plate, options);
  ASSERT_FALSE(job.param.refinement.mesh);  // the loops and vertices are the plate's
  ASSERT_EQ(job.boundary_loops.size(), 2u);
  const int hole =
      std::max_element(job.boundary_loops.begin(), job.boundary_loops.end(), [](const auto& a, const auto& b) {
        return a.first_vertex < b.first_vertex;
      })->loop;
  for (std::size_t k = 0; k < job.boundary_loops.size(); ++k) {
    const BoundaryLoopCheck& c = job.boundary_loops[k];
    expect_loop_matches_mesh(plate, job.boundary_loops, k);
    const double around = c.loop == hole ? 0.2 : 4.0;
    EXPECT_NEAR(c.length, around / job.param.map.edge_length, 1e-9);
  }
  const BoundaryLoopCheck& h = job.boundary_loops[hole - 1];
  EXPECT_EQ(h.non_quads, non_quads(job.extraction.mesh));  // every non-quad is at the hole
  EXPECT_GT(h.non_quads, 0);
  EXPECT_EQ(h.reason.rfind("2.0 grid units around, too short for a ring of quads (4)", 0), 0u) << h.reason;
  EXPECT_NE(h.reason.find("at about 4.0 times the quads"), std::string::npos) << h.reason;
  EXPECT_FALSE(h.closed_over);
  const std::string named = "boundary loop " + std::to_string(hole) + " (through vertex " +
                            std::to_string(h.first_vertex) +
                            " at (0.475, 0.475, 0), 8 edges, 2.0 grid units): " + std::to_string(h.non_quads) +
                            " non-quad faces, " + h.reason;
  EXPECT_NE(std::find(job.param.warnings.begin(), job.param.warnings.end(), named), job.param.warnings.end());

  // By default the clipped polygons around the hole are made quads, and the hole stays.
  options.extraction.quadrangulate_boundary = true;
  const RemeshJob quads = remesh_mesh(plate, options);
  EXPECT_EQ(non_quads(quads.extraction.mesh), 0);
  EXPECT_TRUE(quads.surface.same_topology);
  EXPECT_EQ(quads.surface.output.boundary_loops, 2);
  for (const BoundaryLoopCheck& c : quads.boundary_loops) EXPECT_EQ(c.non_quads, 0);
}

// Issue 14 item 4 / issue 15 item 3: a hole of 1 grid unit around fits inside one quad, which covers it. The quad mesh
// then has one boundary loop fewer than the input, and the hole's record says so (closed over, why, and the density
// that would keep it), as does a warning with its place; the outer loop is followed.
TEST(BoundaryLoopCheck, AHoleTheQuadsCoverIsNamedClosedOverWithItsPlace) {
  const Mesh plate = plate_with_small_hole();
  PipelineOptions options;
  options.param.density.edge_length = 0.2;  // the hole is 0.2 around: 1 grid unit
  options.validity_retries = 0;
  const RemeshJob job = remesh_mesh(plate, options);
  ASSERT_FALSE(job.param.refinement.mesh);
  ASSERT_EQ(job.surface.output.boundary_loops, 1) << "the case this test is about no longer occurs";
  ASSERT_EQ(job.boundary_loops.size(), 2u);
  for (std::size_t k = 0; k < job.boundary_loops.size(); ++k) expect_loop_matches_mesh(plate, job.boundary_loops, k);
  const BoundaryLoopCheck& outer = job.boundary_loops[0];
  const BoundaryLoopCheck& hole = job.boundary_loops[1];
  EXPECT_FALSE(outer.closed_over);
  EXPECT_TRUE(hole.closed_over);
  EXPECT_EQ(hole.reason.rfind("closed over by the quads: 1.0 grid units around, too short for a ring of quads (4)", 0),
            0u)
      << hole.reason;
  EXPECT_NE(hole.reason.find("at about 16.0 times the quads"), std::string::npos) << hole.reason;
  const std::string named = "boundary loop 2 (through vertex " + std::to_string(hole.first_vertex) +
                            " at (0.475, 0.475, 0), 8 edges, 1.0 grid units): " + hole.reason;
  EXPECT_NE(std::find(job.param.warnings.begin(), job.param.warnings.end(), named), job.param.warnings.end());
  EXPECT_TRUE(to_json(job.boundary_loops)[1]["closed_over"].get<bool>());
}

TEST(BoundaryLoopCheck, ALoopOffItsIsoLineSaysWhyAndIsQuadsWhenTheCurvesAreRounded) {
  const Mesh mesh = testing::load_test_mesh("lilium_disk");
  PipelineOptions options;
  options.extraction.quadrangulate_boundary = false;  // the clipped polygons are what is named
  const RemeshJob free_loop = remesh_mesh(mesh, options);
  ASSERT_EQ(free_loop.boundary_loops.size(), 1u);
  const BoundaryLoopCheck& c = free_loop.boundary_loops[0];
  expect_loop_matches_mesh(mesh, free_loop.boundary_loops, 0);
  EXPECT_EQ(c.non_quads, non_quads(free_loop.extraction.mesh));
  EXPECT_GT(c.non_quads, 0);
  EXPECT_EQ(c.enforced_lines, 0);
  EXPECT_NE(c.reason.find("because: closes on itself with another integer"), std::string::npos) << c.reason;
  EXPECT_NE(c.reason.find("--round-curves true puts lines of 3 or more grid units"), std::string::npos) << c.reason;

  options.param.alignment.round_with_periods = true;
  const RemeshJob pinned = remesh_mesh(mesh, options);
  ASSERT_EQ(pinned.boundary_loops.size(), 1u);
  EXPECT_EQ(pinned.boundary_loops[0].non_quads, 0);
  EXPECT_EQ(pinned.boundary_loops[0].enforced_lines, pinned.boundary_loops[0].lines);
  EXPECT_GT(pinned.boundary_loops[0].lines, 0);
  expect_loop_matches_mesh(mesh, pinned.boundary_loops, 0);
}

}  // namespace
}  // namespace quadcover
