// Closed crease loops (field/crease_loops.h) and the side of a short one the field leaves free.
#include "field/crease_loops.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "field/feature_alignment.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

/// The perimeter of the drilled plate's hole: a regular n-gon of circumradius r.
double rim_length(int n, double r) { return 2 * n * r * std::sin(std::numbers::pi / n); }

// The two rims of a hole drilled through a plate are the plate's only closed crease loops (the square's edges meet
// the vertical corner creases at three-crease corners). Each turns by a whole turn on the plate's side (Gauss-Bonnet
// of the flat annulus: the plate's angle at a rim vertex is π + 2π/n) and runs straight along the wall (two right
// angles at each vertex). Recomputed here from those angles, not from the code's fans.
TEST(CreaseLoops, TheRimsOfADrilledHoleTurnAWholeTurnOnThePlateAndNoneOnTheWall) {
  const int n = 16;
  const double r = 0.2;
  const Mesh plate = testing::make_drilled_plate(n, r);
  const std::vector<CreaseLoop> loops = closed_crease_loops(plate, feature_constraints(plate).feature_edges);
  ASSERT_EQ(loops.size(), 2u);
  for (const CreaseLoop& loop : loops) {
    ASSERT_EQ(loop.edges.size(), static_cast<std::size_t>(n));
    EXPECT_NEAR(loop.length, rim_length(n, r), 1e-12);
    for (const int v : loop.vertices) EXPECT_NEAR(std::hypot(plate.V()(v, 0), plate.V()(v, 1)), r, 1e-12);
    const double plate_side = std::abs(loop.turning_left) > 1 ? loop.turning_left : loop.turning_right;
    const double wall_side = std::abs(loop.turning_left) > 1 ? loop.turning_right : loop.turning_left;
    EXPECT_NEAR(std::abs(plate_side), kTwoPi, 1e-9);
    EXPECT_NEAR(wall_side, 0, 1e-9);
    // free_side names the plate's side, and only below the length given
    const int plate_sign = plate_side == loop.turning_left ? 1 : -1;
    EXPECT_EQ(free_side(loop, loop.length * 1.01), plate_sign);
    EXPECT_EQ(free_side(loop, loop.length * 0.99), 0);
  }
}

// A closed curve is a loop; open, or meeting a vertex of three creases, it is none: the plate's top square.
TEST(CreaseLoops, OpenCurvesAndCreasesMeetingAtCornersAreNoLoops) {
  const Mesh plate = testing::make_drilled_plate(16, 0.2);
  std::vector<int> square, corners;  // the top square's 16 edges; the 4 vertical edges at its corners
  for (int e = 0; e < plate.num_edges(); ++e) {
    const Eigen::Vector3d a = plate.V().row(plate.E()(e, 0)), b = plate.V().row(plate.E()(e, 1));
    const bool outer = std::hypot(a.x(), a.y()) > 0.9 && std::hypot(b.x(), b.y()) > 0.9;
    if (outer && a.z() > 0.4 && b.z() > 0.4) square.push_back(e);
    if (outer && (a - b).head<2>().norm() < 1e-12) corners.push_back(e);
  }
  ASSERT_EQ(square.size(), 16u);
  ASSERT_EQ(corners.size(), 16u);  // every vertical outer edge; those at the 4 corners are sharp
  const std::vector<CreaseLoop> loops = closed_crease_loops(plate, square);
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_NEAR(loops[0].length, 8.0, 1e-12);
  std::vector<int> with_corners = square;
  for (const int e : corners)
    if (std::abs(std::abs(plate.V()(plate.E()(e, 0), 0)) - 1) < 1e-12 &&
        std::abs(std::abs(plate.V()(plate.E()(e, 0), 1)) - 1) < 1e-12)
      with_corners.push_back(e);
  ASSERT_EQ(with_corners.size(), 20u);
  EXPECT_TRUE(closed_crease_loops(plate, with_corners).empty());
  const std::vector<int> open(square.begin(), square.end() - 1);
  EXPECT_TRUE(closed_crease_loops(plate, open).empty());
}

// With FeatureOptions::free_short_loops_below above the rim's length, the plate's faces along each rim are no longer
// aligned to it and the wall's still are; below it (and by default) both are.
TEST(CreaseLoops, TheFieldLeavesThePlateSideOfAShortRimFree) {
  const int n = 16;
  const double r = 0.2;
  const Mesh plate = testing::make_drilled_plate(n, r);
  for (const double below : {0.0, 0.99 * rim_length(n, r), 1.01 * rim_length(n, r)}) {
    SCOPED_TRACE(below);
    FeatureOptions options;
    options.free_short_loops_below = below;
    const FeatureConstraints c = feature_constraints(plate, options);
    const bool freed = below > rim_length(n, r);
    int plate_faces = 0, wall_faces = 0;
    for (const CreaseLoop& loop : closed_crease_loops(plate, c.feature_edges))
      for (const int e : loop.edges)
        for (int j = 0; j < 2; ++j) {
          const int f = plate.EF()(e, j);
          const bool on_wall = std::abs(plate.face_normals()(f, 2)) < 1e-9;
          (on_wall ? wall_faces : plate_faces) += 1;
          EXPECT_EQ(c.source_edge[f] == e, on_wall || !freed) << "face " << f;
          EXPECT_EQ(c.constrained[f] != 0, on_wall || !freed) << "face " << f;
        }
    EXPECT_EQ(plate_faces, 2 * n);
    EXPECT_EQ(wall_faces, 2 * n);
  }
}

}  // namespace
}  // namespace quadcover
