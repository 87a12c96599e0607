// The winding of the map around a vertex (param/ring_winding.h): a ring wound the wrong number of turns is laid out
// again with the field's cone angle (the real-mesh case is in tests/pipeline/fold_refinement_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "param/ring_winding.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

/// Signed parameter area of face f.
double signed_area(const Eigen::MatrixX3cd& uv, int f) {
  const Complex e1 = uv(f, 1) - uv(f, 0), e2 = uv(f, 2) - uv(f, 0);
  return 0.5 * (e1.real() * e2.imag() - e1.imag() * e2.real());
}

/// make_fan(n) mapped with its rim wound `turns` times around the apex (at 0), rim vertex k at angle 2π·turns·k/n.
Eigen::MatrixX3cd wound_fan(const Mesh& fan, int turns) {
  const int n = fan.num_faces();
  Eigen::MatrixX3cd uv(n, 3);
  for (int f = 0; f < n; ++f)
    for (int c = 0; c < 3; ++c) {
      const int p = fan.F()(f, c);
      uv(f, c) = p == 0 ? Complex(0) : std::polar(1.0, 2 * std::numbers::pi * turns * (p - 1) / n);
    }
  return uv;
}

TEST(RingWinding, MapQuarterIndexReadsTheWindingOfEveryInteriorVertex) {
  const Mesh fan = testing::make_fan(6, /*closed=*/false);
  EXPECT_EQ(map_quarter_index(fan, wound_fan(fan, 1))[0], 0);
  EXPECT_EQ(map_quarter_index(fan, wound_fan(fan, 2))[0], -4);  // 4π: a fake cone of index −1
  EXPECT_EQ(map_quarter_index(fan, wound_fan(fan, 2))[1], 0);   // rim: boundary
}

TEST(RingWinding, ADoublyWoundRingIsLaidOutWithOneTurnAndEveryFanFacePositive) {
  for (const int n : {5, 6, 9}) {
    SCOPED_TRACE(n);
    const Mesh fan = testing::make_fan(n, /*closed=*/false);
    const Eigen::MatrixX3cd base = wound_fan(fan, 2);
    // Every face of the doubly wound fan is positive: no untangler sees a fold, only the winding tells.
    for (int f = 0; f < fan.num_faces(); ++f) ASSERT_GT(signed_area(base, f), 0);
    const VertexLayers layers{Eigen::MatrixX3i::Zero(fan.num_faces(), 3), Eigen::VectorXi::Zero(fan.num_vertices())};
    const std::vector<char> fixed(static_cast<std::size_t>(2 * fan.num_vertices()), 0);
    RingRewinding out;
    const Eigen::VectorXcd u = rewind_rings(fan, layers, base, Eigen::VectorXcd::Zero(fan.num_vertices()), fixed,
                                            Eigen::VectorXi::Zero(fan.num_vertices()), out);
    ASSERT_EQ(out.rewound, std::vector<int>{0});
    const Eigen::MatrixX3cd uv = base - layered_values(fan, layers, u);
    EXPECT_EQ(map_quarter_index(fan, uv)[0], 0);
    for (int f = 0; f < fan.num_faces(); ++f) EXPECT_GT(signed_area(uv, f), 0) << f;
  }
}

TEST(RingWinding, AHeldRingIsSkippedAndLeftAsItIs) {
  const Mesh fan = testing::make_fan(6, /*closed=*/false);
  const Eigen::MatrixX3cd base = wound_fan(fan, 2);
  const VertexLayers layers{Eigen::MatrixX3i::Zero(fan.num_faces(), 3), Eigen::VectorXi::Zero(fan.num_vertices())};
  std::vector<char> fixed(static_cast<std::size_t>(2 * fan.num_vertices()), 0);
  fixed[0] = fixed[fan.num_vertices()] = 1;  // the apex cannot move to its ring
  fixed[3] = 1;                              // and one ring vertex is held
  RingRewinding out;
  const Eigen::VectorXcd u0 = Eigen::VectorXcd::Zero(fan.num_vertices());
  const Eigen::VectorXcd u = rewind_rings(fan, layers, base, u0, fixed, Eigen::VectorXi::Zero(fan.num_vertices()), out);
  EXPECT_TRUE(out.rewound.empty());
  EXPECT_EQ(out.skipped, std::vector<int>{0});
  EXPECT_EQ(u, u0);
}

}  // namespace
}  // namespace quadcover
