// The whole pipeline on the shipped meshes (field → QuadCover parameterization → extraction): the output is a
// manifold polygon mesh, every iso-line segment is traced, and the quad count matches the parameter-space area.
#include <gtest/gtest.h>

#include <algorithm>

#include "field/compute_frame_field.h"
#include "mesh/surface_counts.h"
#include "param/face_count.h"
#include "param/parameterize.h"
#include "quad/doublets.h"
#include "quad/extract_quads.h"
#include "quad/polygon_check.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

class ShippedMeshes : public ::testing::TestWithParam<const char*> {};

TEST_P(ShippedMeshes, ExtractionIsManifoldAndCountsMatchArea) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  const Parameterization P = parameterize(mesh, compute_frame_field(mesh));
  const ExtractionResult res = extract_quads(mesh, P);
  const ExtractionReport& r = res.report;
  const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
  const double area = parameter_area(mesh, P.uv);
  EXPECT_EQ(t.non_manifold_edges + t.inconsistent_edges, 0);
  EXPECT_EQ(t.non_manifold_vertices, 0);
  EXPECT_EQ(t.degenerate_faces, 0);
  EXPECT_EQ(r.failed_traces, 0);
  if (r.flipped_triangles + r.degenerate_triangles == 0) {
    EXPECT_EQ(r.dropped_faces, 0);
  }
  EXPECT_EQ(r.torn_seams, 0);
  // The report is honest: an independent check of the same faces agrees, and no vertex is left unused.
  const testing::PolygonCheck pc = testing::check_polygons(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_EQ(pc.problems, 0);
  EXPECT_EQ(pc.unreferenced, 0);
  EXPECT_EQ(t.isolated_vertices, 0);
  EXPECT_EQ(t.manifold() && t.oriented(), pc.problems == 0);
  EXPECT_EQ(t.euler_characteristic, pc.euler());
  EXPECT_EQ(t.boundary_edges, pc.boundary_edges);
  // No spurious handles: capping every boundary loop with a disk, the output's total genus is at most the
  // input's (it lies on the input surface): χ̂ − 2·components can only grow.
  const int capped_in = mesh.euler_characteristic() + mesh.num_boundary_loops() - 2 * mesh.num_components();
  EXPECT_GE(pc.euler() + pc.boundary_loops - 2 * pc.components, capped_in);
  // No closed debris (e.g. two quads glued along all sides inside a fold), and closing fold holes never turns a
  // small piece into a closed blob: a closed output component has at least the 6 faces of a cube.
  if (pc.components > 1) {
    for (const auto& piece : testing::split_components(res.mesh.faces)) {
      const testing::PolygonCheck c = testing::check_polygons(res.mesh.num_vertices(), piece);
      if (c.boundary_edges == 0) {
        EXPECT_GE(c.faces, 6) << "closed piece of " << c.faces << " faces";
      }
    }
  }
  // A closed all-quad output of a closed input is the same surface with one quad per unit of parameter area.
  if (mesh.num_boundary_loops() == 0 && t.closed() && r.non_quads == 0) {
    EXPECT_EQ(t.euler_characteristic, mesh.euler_characteristic());
    if (r.split_polygons + r.merged_polygons + r.flipped_triangles + r.degenerate_triangles + r.removed_doublets == 0) {
      EXPECT_NEAR(r.quads, r.active_parameter_area, 1e-6 * area);
    }
  }
  // Each quad is one unit cell of the parameter domain. Polygons around cut-out folds are merged cells (at most 4
  // cells each) and faces at the boundary partial cells (the clipped polygons, also when made quads), so the count
  // is the extracted area up to them; polygons split into quads (quadrangulate.h) are such cells too.
  const std::vector<char> on_boundary = quad_boundary_vertices(res.mesh);
  const auto at_boundary = std::count_if(res.mesh.faces.begin(), res.mesh.faces.end(), [&](const auto& f) {
    return std::any_of(f.begin(), f.end(), [&](int v) { return on_boundary[v] != 0; });
  });
  const int repaired = r.non_quads + r.split_polygons + r.merged_polygons + r.removed_doublets;
  EXPECT_NEAR(r.quads, r.active_parameter_area, 4.0 * repaired + static_cast<double>(at_boundary) + 1e-6 * area)
      << "non-quads " << r.non_quads << ", split " << r.split_polygons << ", merged " << r.merged_polygons
      << ", cut out: " << r.flipped_triangles << " flipped, " << r.degenerate_triangles << " degenerate";
  // A valid map of a closed surface with cones on grid points extracts to quads only.
  bool cones_on_grid = true;
  for (const BranchPoint& b : P.branch_points)
    for (const auto& fc : mesh.fan(b.vertex)) {
      const Complex z = P.uv(fc.face, fc.corner);
      cones_on_grid &= std::abs(z - Complex(std::round(z.real()), std::round(z.imag()))) < 1e-6;
    }
  if (mesh.num_boundary_loops() == 0 && r.flipped_triangles + r.degenerate_triangles == 0 && cones_on_grid) {
    EXPECT_EQ(r.non_quads, 0);
  }
  EXPECT_GT(r.quads, 0.5 * area);
  // Doublets (quad/doublets.h) were removed last: none is left that could go.
  QuadMesh again = res.mesh;
  EXPECT_EQ(remove_doublets(again), 0);
}
INSTANTIATE_TEST_SUITE_P(Meshes, ShippedMeshes,
                         ::testing::Values("bunny_3k", "torus_5k", "eight_genus2", "3holes_genus3", "fertility_genus4",
                                           "lilium_disk", "camelhead_boundary", "spot", "fandisk", "cow",
                                           "couplingdown_genus9", "mech_holes_shark", "bunny_20k_holes"));

}  // namespace
}  // namespace quadcover

namespace quadcover {
namespace {

// Issue 7 / Table 7.1 setting: the closed bunny at about 6500 output vertices extracts to a closed all-quad
// manifold mesh of the input's topology (sphere, χ = 2) with about one quad per unit of parameter area. Branch
// points rounded onto the same integer point are merged by the edge collapse, folds are untangled; a fold that
// cannot be (next to a cone) is cut out, its hole closed and the cells around it re-split into quads.
TEST(ShippedMeshes, BunnyAtTable71DensityIsClosedAllQuad) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  ParamOptions po;
  po.density.target_quads = 6500;
  const Parameterization P = parameterize(mesh, compute_frame_field(mesh), po);
  const ExtractionResult res = extract_quads(mesh, P);
  const testing::PolygonCheck pc = testing::check_polygons(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_EQ(pc.problems, 0);
  EXPECT_EQ(pc.unreferenced, 0);
  EXPECT_EQ(pc.boundary_edges, 0);
  EXPECT_EQ(pc.components, 1);
  EXPECT_EQ(pc.euler(), 2);
  EXPECT_EQ(res.report.non_quads, 0);
  EXPECT_GT(res.report.quads, 5500);
  EXPECT_LT(res.report.quads, 7500);
  // The fold repair moves vertices only: on a closed surface the signed parameter area of the map is unchanged, and
  // it is the quad count; cells around a fold that had to be cut out (hole closed, polygons re-split) may differ
  // from it by a few quads each.
  double signed_area = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Complex e1 = P.uv(f, 1) - P.uv(f, 0), e2 = P.uv(f, 2) - P.uv(f, 0);
    signed_area += 0.5 * (e1.real() * e2.imag() - e1.imag() * e2.real());
  }
  const ExtractionReport& r = res.report;
  const int repairs = r.flipped_triangles + r.degenerate_triangles + r.split_polygons + r.merged_polygons + r.filled_holes;
  EXPECT_NEAR(r.quads, signed_area, 4.0 * repairs + 1e-6 * r.quads);
  if (repairs == 0) {
    EXPECT_NEAR(r.quads, r.active_parameter_area, 1e-6 * r.quads);
  }
}

}  // namespace
}  // namespace quadcover
