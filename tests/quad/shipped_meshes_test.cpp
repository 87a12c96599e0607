// The whole pipeline on the shipped meshes (field → QuadCover parameterization → extraction): the output is a
// manifold polygon mesh, every iso-line segment is traced, and the quad count matches the parameter-space area.
#include <gtest/gtest.h>

#include "field/compute_frame_field.h"
#include "param/parameterize.h"
#include "quad/extract_quads.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

class ShippedMeshes : public ::testing::TestWithParam<const char*> {};

TEST_P(ShippedMeshes, ExtractionIsManifoldAndCountsMatchArea) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  const Parameterization P = parameterize(mesh, compute_frame_field(mesh));
  const ExtractionResult res = extract_quads(mesh, P);
  const ExtractionReport& r = res.report;
  const PolygonTopology t = polygon_topology(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_EQ(t.non_manifold_edges, 0);
  EXPECT_EQ(t.non_manifold_vertices, 0);
  EXPECT_EQ(t.degenerate_faces, 0);
  EXPECT_EQ(r.failed_traces, 0);
  if (r.flipped_triangles + r.degenerate_triangles == 0) EXPECT_EQ(r.dropped_faces, 0);
  EXPECT_EQ(r.torn_seams, 0);
  // Each quad is one unit cell of the parameter domain. Polygons at the boundary or around cut-out folds are
  // partial or merged cells (at most 4 cells each), so the count is the extracted area up to them.
  const double area = parameter_area(mesh, P.uv);
  EXPECT_NEAR(r.quads, r.active_parameter_area, 4.0 * r.non_quads + 1e-6 * area)
      << "non-quads " << r.non_quads << ", cut out: " << r.flipped_triangles << " flipped, " << r.degenerate_triangles
      << " degenerate";
  // A valid map of a closed surface with cones on grid points extracts to quads only.
  bool cones_on_grid = true;
  for (const BranchPoint& b : P.branch_points)
    for (const auto& fc : mesh.fan(b.vertex)) {
      const Complex z = P.uv(fc.face, fc.corner);
      cones_on_grid &= std::abs(z - Complex(std::round(z.real()), std::round(z.imag()))) < 1e-6;
    }
  if (mesh.num_boundary_loops() == 0 && r.flipped_triangles + r.degenerate_triangles == 0 && cones_on_grid)
    EXPECT_EQ(r.non_quads, 0);
  EXPECT_GT(r.quads, 0.5 * area);
}
INSTANTIATE_TEST_SUITE_P(Meshes, ShippedMeshes,
                         ::testing::Values("bunny_3k", "torus_5k", "eight_genus2", "3holes_genus3", "fertility_genus4",
                                           "lilium_disk", "camelhead_boundary", "spot", "fandisk", "cow",
                                           "couplingdown_genus9"));

}  // namespace
}  // namespace quadcover
