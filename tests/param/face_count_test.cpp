// The face count a map predicts (param/face_count.h): area, and half the boundary where it cuts cells.
#include "param/face_count.h"

#include <gtest/gtest.h>

#include <numbers>

#include "support/test_meshes.h"

namespace quadcover {
namespace {

/// The map z ↦ scale · z · rotation + shift of the unit square's grid, per corner.
Eigen::MatrixX3cd square_map(const Mesh& grid, double scale, Complex rotation, Complex shift) {
  Eigen::MatrixX3cd uv(grid.num_faces(), 3);
  for (int f = 0; f < grid.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const auto p = grid.V().row(grid.F()(f, c));
      uv(f, c) = scale * Complex(p.x(), p.y()) * rotation + shift;
    }
  return uv;
}

TEST(FaceCount, ABoundaryOnIntegerIsoLinesCutsNoCell) {
  const Mesh grid = testing::make_grid(6);
  const Eigen::MatrixX3cd uv = square_map(grid, 5.0, 1.0, 0.0);  // 5 × 5 cells, the sides on u, v = 0, 5
  EXPECT_NEAR(parameter_area(grid, uv), 25.0, 1e-12);
  EXPECT_NEAR(cut_boundary_length(grid, uv), 0.0, 1e-12);
  EXPECT_NEAR(expected_face_count(grid, uv), 25.0, 1e-12);
}

// Before the rounding the translations are not integers: slanted_boundary_length counts a side along an axis as one
// that will be on an iso-line, whatever the shift, and a slanted side as cutting cells.
TEST(FaceCount, AShiftedOrTurnedBoundaryCountsHalfItsLength) {
  const Mesh grid = testing::make_grid(6);
  const Eigen::MatrixX3cd shifted = square_map(grid, 5.0, 1.0, Complex(0.5, 0.5));
  EXPECT_NEAR(cut_boundary_length(grid, shifted), 20.0, 1e-12);
  EXPECT_NEAR(expected_face_count(grid, shifted), 25.0 + 10.0, 1e-12);
  EXPECT_NEAR(slanted_boundary_length(grid, shifted, 0.05), 0.0, 1e-12);
  // Half a side shifted: only the two sides across the shift stay on iso-lines.
  const Eigen::MatrixX3cd half = square_map(grid, 5.0, 1.0, Complex(0.5, 0.0));
  EXPECT_NEAR(cut_boundary_length(grid, half), 10.0, 1e-12);
  // Turned by 45°: every side cuts cells; the area does not change.
  const Eigen::MatrixX3cd turned = square_map(grid, 5.0, std::polar(1.0, 0.25 * std::numbers::pi), 0.0);
  EXPECT_NEAR(parameter_area(grid, turned), 25.0, 1e-9);
  EXPECT_NEAR(cut_boundary_length(grid, turned), 20.0, 1e-9);
  EXPECT_NEAR(slanted_boundary_length(grid, turned, 0.05), 20.0, 1e-9);
}

TEST(FaceCount, SlantedBoundaryHasATurnTolerance) {
  const Mesh grid = testing::make_grid(6);
  const Eigen::MatrixX3cd slightly = square_map(grid, 5.0, std::polar(1.0, 0.03), Complex(0.3, 0.7));
  EXPECT_NEAR(slanted_boundary_length(grid, slightly, 0.05), 0.0, 1e-12);  // within the tolerance
  EXPECT_NEAR(slanted_boundary_length(grid, slightly, 0.02), 20.0, 1e-9);
}

TEST(FaceCount, AFoldedTriangleCountsItsAreaOnce) {
  const Mesh grid = testing::make_grid(2);
  Eigen::MatrixX3cd uv = square_map(grid, 2.0, 1.0, 0.0);
  uv.row(0) = uv.row(0).reverse().eval();  // one triangle's image reflected: |area| stays
  EXPECT_NEAR(parameter_area(grid, uv), 4.0, 1e-12);
}

}  // namespace
}  // namespace quadcover
