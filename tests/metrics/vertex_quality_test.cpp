// Per-vertex quality of a polygon mesh (PLY `quality` / `valence`): a square grid is perfect (0° deviation, valence
// 4 inside, 3 on the sides, 2 at the corners); a sheared quad and a triangle are measured against 90° and 60°.
#include "metrics/vertex_quality.h"

#include <gtest/gtest.h>

#include <cmath>

namespace quadcover {
namespace {

TEST(VertexQuality, SquareGridIsPerfect) {
  const int n = 4;
  Eigen::MatrixX3d V((n + 1) * (n + 1), 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) V.row(j * (n + 1) + i) << i, j, 0.1 * i * j;  // a saddle: not planar quads
  std::vector<std::vector<int>> faces;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int v = j * (n + 1) + i;
      faces.push_back({v, v + 1, v + n + 2, v + n + 1});
    }
  const VertexQuality q = vertex_quality(V, faces);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const int v = j * (n + 1) + i, sides = (i == 0 || i == n) + (j == 0 || j == n);
      EXPECT_EQ(q.valence[v], 4 - sides) << i << "," << j;
    }
  // The saddle z = 0.1 x y: corner angles differ from 90° by acos-computable amounts, largest at the far corner.
  EXPECT_LT(q.worst_angle_deviation.maxCoeff(), 15.0);
  EXPECT_EQ(q.worst_angle_deviation[0], 0.0);  // at the origin the corner is exactly 90°
  Eigen::MatrixX3d flat = V;
  flat.col(2).setZero();
  EXPECT_LT(vertex_quality(flat, faces).worst_angle_deviation.maxCoeff(), 1e-12);
}

TEST(VertexQuality, ShearedQuadAndTriangle) {
  Eigen::MatrixX3d V(5, 3);
  const double s = 0.5, h = std::sqrt(3.0) / 2;  // parallelogram with 60° / 120° corners
  V << 0, 0, 0, 1, 0, 0, 1 + s, h, 0, s, h, 0, 2.5, 0, 0;
  const VertexQuality quad = vertex_quality(V, {{0, 1, 2, 3}});
  for (int v = 0; v < 4; ++v) EXPECT_NEAR(quad.worst_angle_deviation[v], 30.0, 1e-9);
  EXPECT_EQ(quad.worst_angle_deviation[4], 0.0);  // unused
  EXPECT_EQ(quad.valence[4], 0);
  // An equilateral triangle: its corners are measured against 60°.
  Eigen::MatrixX3d T(3, 3);
  T << 0, 0, 0, 1, 0, 0, 0.5, h, 0;
  const VertexQuality tri = vertex_quality(T, {{0, 1, 2}});
  for (int v = 0; v < 3; ++v) EXPECT_NEAR(tri.worst_angle_deviation[v], 0.0, 1e-9);
  // A zero-length edge is the worst case.
  Eigen::MatrixX3d D = T;
  D.row(2) = D.row(1);
  EXPECT_EQ(vertex_quality(D, {{0, 1, 2}}).worst_angle_deviation[1], 180.0);
}

}  // namespace
}  // namespace quadcover
