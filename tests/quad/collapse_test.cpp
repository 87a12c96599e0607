// Collapse of edges the map sends to a point (quad/collapse_degenerate.h): topology, seamlessness of the composed
// transitions, and the quad mesh extracted afterwards.
#include "quad/collapse_degenerate.h"

#include <gtest/gtest.h>

#include "param/face_count.h"
#include "quad/extract_quads.h"
#include "quad/integer_grid_map.h"
#include "quad/polygon_check.h"
#include "quad/quad_test_maps.h"

namespace quadcover {
namespace {

// Torus map with vertex b moved onto its neighbour a in every chart (translations only, so one displacement works
// for all charts): the two triangles of edge ab have zero parameter area.
testing::MeshAndMap torus_with_collapsed_edge(int a, int& b) {
  auto m = testing::torus_map(24, 12, 17, 7);
  const auto fc = m.mesh.fan(a)[0];
  b = m.mesh.F()(fc.face, (fc.corner + 1) % 3);
  const Complex delta = m.param.uv(fc.face, fc.corner) - m.param.uv(fc.face, (fc.corner + 1) % 3);
  for (const auto& g : m.mesh.fan(b)) m.param.uv(g.face, g.corner) += delta;
  return m;
}

// Across every interior edge the corner values satisfy φ_t = i^k φ_s + c exactly (thesis 4.2.2).
double max_seam_error(const Mesh& mesh, const Parameterization& p) {
  double err = 0;
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    if (s < 0 || t < 0) continue;
    for (int j = 0; j < 2; ++j) {
      const int v = mesh.E()(e, j);
      const Complex zs = p.uv(s, grid::local_corner(mesh, s, v)), zt = p.uv(t, grid::local_corner(mesh, t, v));
      err = std::max(err, std::abs(zt - (ipow(p.transition_rotation[e]) * zs + p.transition_translation[e])));
    }
  }
  return err;
}

// Vertex 0 lies on the period seams of torus_map, so the glued triangles meet across seams (composed transitions).
TEST(CollapseZeroEdges, TorusEdgeOnTheSeams) {
  for (int a : {0, 37}) {
    int b = -1;
    const auto [mesh, param] = torus_with_collapsed_edge(a, b);
    const CollapsedMap c = collapse_zero_edges(mesh, param, 1e-9);
    ASSERT_EQ(c.collapsed_edges, 1);
    EXPECT_EQ(c.mesh.num_faces(), mesh.num_faces() - 2);
    EXPECT_EQ(c.mesh.num_vertices(), mesh.num_vertices() - 1);
    EXPECT_EQ(c.mesh.euler_characteristic(), mesh.euler_characteristic());
    EXPECT_EQ(c.mesh.num_boundary_loops(), 0);
    EXPECT_LT(max_seam_error(mesh, param), 1e-12);
    EXPECT_LT(max_seam_error(c.mesh, c.param), 1e-12);
    ASSERT_EQ(static_cast<int>(c.face_origin.size()), c.mesh.num_faces());
    for (int f = 0; f < c.mesh.num_faces(); ++f) EXPECT_EQ(c.param.uv.row(f), param.uv.row(c.face_origin[f]));
    // The parameter area is unchanged (the removed triangles had none).
    EXPECT_NEAR(parameter_area(c.mesh, c.param.uv), parameter_area(mesh, param.uv), 1e-9);
    // Extraction: the exact torus quad mesh, with the collapse reported; without it (and
    // without the fold repair) the two triangles are cut out.
    const ExtractionResult res = extract_quads(mesh, param);
    EXPECT_EQ(res.report.collapsed_edges, 1);
    EXPECT_EQ(res.report.degenerate_triangles, 0);
    EXPECT_EQ(res.mesh.num_quads(), 17 * 7);
    EXPECT_EQ(res.mesh.num_faces(), 17 * 7);
    const testing::PolygonCheck pc = testing::check_polygons(res.mesh.num_vertices(), res.mesh.faces);
    EXPECT_EQ(pc.problems, 0);
    EXPECT_EQ(pc.boundary_edges, 0);
    EXPECT_EQ(pc.euler(), 0);
    for (int v = 0; v < res.mesh.num_vertices(); ++v) {
      EXPECT_GE(res.mesh.source_face[v], 0);
      EXPECT_LT(res.mesh.source_face[v], mesh.num_faces());
    }
    ExtractOptions no_collapse;
    no_collapse.collapse_zero_edges = false;
    no_collapse.repair_folds = false;  // (a and b are regular here: the repair alone could pull b off a)
    const ExtractionResult cut = extract_quads(mesh, param, no_collapse);
    EXPECT_EQ(cut.report.collapsed_edges, 0);
    EXPECT_GE(cut.report.degenerate_triangles, 2);
  }
}

// Nothing to collapse on a valid map; edges at the boundary are never collapsed.
TEST(CollapseZeroEdges, LeavesValidMapsAndBoundariesAlone) {
  const auto [mesh, param] = testing::torus_map(24, 12, 17, 7);
  EXPECT_EQ(collapse_zero_edges(mesh, param, 1e-9).collapsed_edges, 0);
  auto [sq, sp] = testing::square_map(4, 6.0, 0.0, {0, 0});
  // Put boundary vertex 1 onto boundary vertex 0 (their edge lies on the boundary).
  for (const auto& g : sq.fan(1)) sp.uv(g.face, g.corner) = sp.uv(sq.fan(0)[0].face, sq.fan(0)[0].corner);
  EXPECT_EQ(collapse_zero_edges(sq, sp, 1e-9).collapsed_edges, 0);
}

}  // namespace
}  // namespace quadcover
