// SegmentGrid against brute force on random, degenerate and far-away queries.
#include "mesh/segment_grid.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace quadcover {
namespace {

double brute_force(const Eigen::MatrixX3d& V, const Eigen::MatrixX2i& E, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (int s = 0; s < E.rows(); ++s)
    best = std::min(best, (closest_point_on_segment(p, V.row(E(s, 0)), V.row(E(s, 1))) - p).squaredNorm());
  return best;
}

TEST(SegmentGrid, ClosestPointOnSegment) {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0);
  EXPECT_TRUE(closest_point_on_segment({1, 1, 0}, a, b).isApprox(Eigen::Vector3d(1, 0, 0)));
  EXPECT_TRUE(closest_point_on_segment({-1, 1, 0}, a, b).isApprox(a));
  EXPECT_TRUE(closest_point_on_segment({5, 1, 0}, a, b).isApprox(b));
  EXPECT_TRUE(closest_point_on_segment({5, 1, 0}, a, a).isApprox(a));
}

TEST(SegmentGrid, MatchesBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), small(-0.1, 0.1);
  const int n = 400;
  Eigen::MatrixX3d V(2 * n, 3);
  Eigen::MatrixX2i E(n, 2);
  for (int s = 0; s < n; ++s) {
    // Short segments on a flat sheet (as a remesh's edges), a few long ones and a few points.
    const Eigen::Vector3d a(u(rng), u(rng), 0.01 * u(rng));
    const Eigen::Vector3d d = s % 50 == 0   ? Eigen::Vector3d(u(rng), u(rng), u(rng)) * 2
                              : s % 37 == 0 ? Eigen::Vector3d::Zero()
                                            : Eigen::Vector3d(small(rng), small(rng), 0.01 * small(rng));
    V.row(2 * s) = a.transpose();
    V.row(2 * s + 1) = (a + d).transpose();
    E.row(s) << 2 * s, 2 * s + 1;
  }
  const SegmentGrid grid(V, E);
  for (int i = 0; i < 2000; ++i) {
    const double scale = i % 10 == 0 ? 30.0 : 1.2;  // some queries far outside the grid
    const Eigen::Vector3d p(scale * u(rng), scale * u(rng), scale * 0.3 * u(rng));
    int s = -1;
    const double d2 = grid.squared_distance(p, &s);
    ASSERT_NEAR(d2, brute_force(V, E, p), 1e-12);
    ASSERT_GE(s, 0);
    const Eigen::Vector3d q = grid.closest_point(p);
    EXPECT_NEAR((q - p).squaredNorm(), d2, 1e-12);
  }
}

TEST(SegmentGrid, EmptyAndSingle) {
  const SegmentGrid empty(Eigen::MatrixX3d(0, 3), Eigen::MatrixX2i(0, 2));
  int s = 0;
  EXPECT_EQ(empty.squared_distance({1, 2, 3}, &s), std::numeric_limits<double>::infinity());
  EXPECT_EQ(s, -1);
  Eigen::MatrixX3d V(2, 3);
  V << 0, 0, 0, 0, 0, 1;  // a segment along z: a grid flat in x and y
  Eigen::MatrixX2i E(1, 2);
  E << 0, 1;
  const SegmentGrid one(V, E);
  EXPECT_NEAR(one.squared_distance({3, 4, 0.5}), 25.0, 1e-12);
  EXPECT_NEAR(one.squared_distance({0, 0, -2}), 4.0, 1e-12);
}

}  // namespace
}  // namespace quadcover
