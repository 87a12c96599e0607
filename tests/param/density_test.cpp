// The default density (param/density.h): made finer for short boundary loops, so that a small hole keeps a ring of
// quads (issue 14 item 4, issue 15 item 3), within a cap, and never when the user gave a density; and finer on the
// small components of a mesh, so that each has quads enough for its branch points.
#include "param/density.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "field/compute_frame_field.h"
#include "field/indices.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

/// make_grid(n) with its ((n − 2) / 2)² square holes of one cell (perimeter 4 / n).
Mesh plate_with_holes(int n) {
  const Mesh grid = testing::make_grid(n);
  return Mesh::from_triangles(grid.V(), testing::grid_faces_with_holes(grid, n));
}

/// The default h without the loop rule.
double unraised_edge_length(const Mesh& mesh) {
  DensityOptions o;
  o.min_loop_grid_units = 0;
  return target_edge_length(mesh, o);
}

TEST(DefaultDensity, IsMadeFinerUntilTheShortestHoleIsFourQuadEdgesAround) {
  const Mesh plate = plate_with_holes(10);
  ASSERT_EQ(plate.num_boundary_loops(), 17);
  const double h = unraised_edge_length(plate);
  ASSERT_LT(0.4 / h, 4.0);  // the holes are shorter than 4 h: without the rule the quads close over them
  const LoopResolution r = loop_resolution(plate, DensityOptions{}, h);
  ASSERT_GE(r.loop, 0);
  EXPECT_NEAR(r.length, 0.4, 1e-12);
  EXPECT_NEAR(r.quads_factor, std::pow(h / 0.1, 2), 1e-9);
  const auto& loop = plate.boundary_loops()[r.loop];
  EXPECT_EQ(loop.size(), 4u);  // a hole, not the outer loop
  EXPECT_EQ(r.lowest_vertex, *std::min_element(loop.begin(), loop.end()));
  EXPECT_NEAR(target_edge_length(plate, DensityOptions{}), 0.1, 1e-12);  // 0.4 long = 4 h
}

TEST(DefaultDensity, StaysWhereTheLoopsAreLongOrTooShortForTheCap) {
  const Mesh grid = testing::make_grid(10);  // one loop of length 4, about 17 h
  EXPECT_EQ(loop_resolution(grid, DensityOptions{}, unraised_edge_length(grid)).loop, -1);
  EXPECT_DOUBLE_EQ(target_edge_length(grid, DensityOptions{}), unraised_edge_length(grid));
  const Mesh plate = plate_with_holes(10);
  const double h = unraised_edge_length(plate);
  DensityOptions capped;
  capped.max_loop_quads_factor = 0.5 * std::pow(h / 0.1, 2);  // the holes would need twice that
  const LoopResolution r = loop_resolution(plate, capped, h);
  EXPECT_EQ(r.loop, -1);
  EXPECT_EQ(r.quads_factor, 1.0);
  EXPECT_DOUBLE_EQ(target_edge_length(plate, capped), h);
  // 6 quad edges around a hole: within the factor cap, but more quads than the plate has triangles.
  DensityOptions six;
  six.min_loop_grid_units = 6;
  ASSERT_LT(std::pow(h / (0.4 / 6), 2), six.max_loop_quads_factor);
  ASSERT_GT(plate.total_area() / std::pow(0.4 / 6, 2), plate.num_faces());
  EXPECT_EQ(loop_resolution(plate, six, h).loop, -1);
  six.min_loop_grid_units = 5;  // 0.08: fewer quads than triangles
  ASSERT_LT(plate.total_area() / std::pow(0.08, 2), plate.num_faces());
  EXPECT_NEAR(target_edge_length(plate, six), 0.08, 1e-12);
  DensityOptions off;
  off.min_loop_grid_units = 0;
  EXPECT_EQ(loop_resolution(plate, off, h).loop, -1);
}

// A hole rim (DensityOptions::hole_rims: a crease loop round a hole through the part) is held to the same four quad
// edges as a boundary loop; the shorter of a rim and a boundary loop wins.
TEST(DefaultDensity, HoleRimsAreMadeFourQuadEdgesAroundAsBoundaryLoopsAre) {
  const Mesh grid = testing::make_grid(10);  // its one boundary loop is about 17 h long
  const double h = unraised_edge_length(grid);
  DensityOptions rims;
  rims.hole_rims = {{7, 2.0 * h}, {3, 2.5 * h}};
  const LoopResolution r = loop_resolution(grid, rims, h);
  EXPECT_TRUE(r.rim);
  EXPECT_EQ(r.loop, 0);
  EXPECT_EQ(r.lowest_vertex, 7);
  EXPECT_NEAR(r.length, 2.0 * h, 1e-12);
  EXPECT_NEAR(r.quads_factor, 4.0, 1e-9);  // h → h / 2
  EXPECT_NEAR(target_edge_length(grid, rims), 0.5 * h, 1e-12);
  const Mesh plate = plate_with_holes(10);  // holes 0.4 long: shorter than a rim of 0.5
  rims.hole_rims = {{0, 0.5}};
  const double plate_h = unraised_edge_length(plate);
  EXPECT_FALSE(loop_resolution(plate, rims, plate_h).rim);
  rims.hole_rims = {{0, 0.3}};
  EXPECT_TRUE(loop_resolution(plate, rims, plate_h).rim);
}

TEST(DefaultDensity, AGivenDensityIsNeverChanged) {
  const Mesh plate = plate_with_holes(10);
  const FrameField none;  // not read for an explicit density
  for (const bool by_count : {true, false}) {
    DensityOptions o;
    if (by_count)
      o.target_quads = 20;
    else
      o.edge_length = 0.3;
    const DensityOptions given = o;
    EXPECT_EQ(fix_default_density(plate, none, o).loop, -1);
    EXPECT_EQ(o.edge_length, given.edge_length);
    EXPECT_EQ(o.target_quads, given.target_quads);
    EXPECT_NEAR(target_edge_length(plate, o), by_count ? std::sqrt(plate.total_area() / 20) : 0.3, 1e-12);
  }
}

/// Per component: area and branch points of `field`.
std::pair<std::vector<double>, std::vector<int>> area_and_branch_points(const Mesh& mesh, const FrameField& field) {
  std::vector<double> area(mesh.num_components(), 0.0);
  std::vector<int> branch(mesh.num_components(), 0);
  for (int f = 0; f < mesh.num_faces(); ++f) area[mesh.face_component()[f]] += mesh.face_areas()[f];
  for (const BranchPoint& bp : branch_points(mesh, field)) ++branch[mesh.vertex_component()[bp.vertex]];
  return {area, branch};
}

TEST(ComponentDensity, GivesASmallComponentTheQuadsItsBranchPointsAsk) {
  const Mesh mesh = testing::scaled_copies(testing::make_ellipsoid(3, 1.0, 0.8, 0.6), {1.0, 0.1});
  ASSERT_EQ(mesh.num_components(), 2);
  const FrameField field = compute_frame_field(mesh);
  const auto [area, branch] = area_and_branch_points(mesh, field);
  ASSERT_GT(branch[0], 0);
  ASSERT_GT(branch[1], 0);
  DensityOptions o;
  const double h = target_edge_length(mesh, o, branch[0] + branch[1]);
  ASSERT_LT(area[1] / (h * h), o.min_quads_per_branch_point * branch[1]);  // one h leaves the copy too few quads
  ASSERT_TRUE(fix_component_density(mesh, field, h, o));
  ASSERT_EQ(o.component_density.size(), 2u);
  EXPECT_EQ(o.component_density[0], 1.0);  // the large one has enough already
  const double rho = o.component_density[1];
  EXPECT_NEAR(area[1] * rho * rho / (h * h), o.min_quads_per_branch_point * branch[1], 1e-9 * area[1] / (h * h));
  const Eigen::VectorXd per_face = face_density(mesh, o.component_density);
  for (int f = 0; f < mesh.num_faces(); ++f) EXPECT_EQ(per_face[f], o.component_density[mesh.face_component()[f]]);
  // At most one quad per triangle of the component.
  DensityOptions many;
  many.min_quads_per_branch_point = 1e6;
  ASSERT_TRUE(fix_component_density(mesh, field, h, many));
  const double capped = many.component_density[1];
  EXPECT_NEAR(area[1] * capped * capped / (h * h), mesh.components()[1].faces, 1e-9 * mesh.components()[1].faces);
}

TEST(ComponentDensity, StaysEmptyOnOneComponentOrWhereEveryComponentHasEnough) {
  const Mesh one = testing::make_ellipsoid(3);
  const FrameField field = compute_frame_field(one);
  DensityOptions o;
  EXPECT_FALSE(fix_component_density(one, field, target_edge_length(one, o, 8), o));
  EXPECT_TRUE(o.component_density.empty());
  EXPECT_EQ(face_density(one, o.component_density), Eigen::VectorXd::Ones(one.num_faces()));
  const Mesh two = testing::scaled_copies(testing::make_ellipsoid(3), {1.0, 1.0});  // one h suits both
  const FrameField both = compute_frame_field(two);
  const int count = static_cast<int>(branch_points(two, both).size());
  EXPECT_FALSE(fix_component_density(two, both, target_edge_length(two, o, count), o));
  EXPECT_TRUE(o.component_density.empty());
}

}  // namespace
}  // namespace quadcover
