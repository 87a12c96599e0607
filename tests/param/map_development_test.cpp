// The map around a vertex developed into one chart (param/map_development.h): charts that differ by a quarter turn
// and a translation across a seam are brought back into one, reading each transition at a regular vertex.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "param/map_development.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

/// The position of fan vertex v in the plane: apex at 0, rim vertex k at angle 2πk/n.
Complex flat(const Mesh& fan, int v) {
  const int n = fan.num_faces();
  return v == 0 ? Complex(0) : std::polar(1.0, 2 * std::numbers::pi * (v - 1) / n);
}

/// A fan whose faces from `seam` on are given in a chart turned by i and moved by (3, −2), with layers that say so.
struct TurnedFan {
  Mesh mesh = testing::make_fan(6, /*closed=*/false);
  Eigen::MatrixX3cd base;
  VertexLayers layers;
  explicit TurnedFan(int seam) {
    const int n = mesh.num_faces();
    base.resize(n, 3);
    layers = {Eigen::MatrixX3i::Zero(n, 3), Eigen::VectorXi::Zero(mesh.num_vertices())};
    for (int f = 0; f < n; ++f)
      for (int c = 0; c < 3; ++c) {
        const bool turned = f >= seam;
        base(f, c) = turned ? Complex(0, 1) * flat(mesh, mesh.F()(f, c)) + Complex(3, -2) : flat(mesh, mesh.F()(f, c));
        layers.layer(f, c) = turned ? 1 : 0;
      }
  }
};

TEST(MapDevelopment, TurnedChartsComeBackIntoTheFirstFacesChart) {
  const TurnedFan t(3);
  const Eigen::VectorXcd zero = Eigen::VectorXcd::Zero(t.mesh.num_vertices());
  const auto around = developed_around(t.mesh, t.layers, t.base, zero, 0, 2);
  ASSERT_EQ(around.size(), 3u * t.mesh.num_faces());  // every face reached
  for (const auto& [v, z] : around) EXPECT_LT(std::abs(z - flat(t.mesh, v)), 1e-12) << v;
  // The raw corner values of the turned faces are elsewhere: the development did the work.
  EXPECT_GT(std::abs(t.base(4, 1) - flat(t.mesh, t.mesh.F()(4, 1))), 1);
}

TEST(MapDevelopment, TransitionsAreReadAtRegularVerticesOnly) {
  // The apex and rim vertex 1 made branch points, their layers meaningless: the spoke 0–1 between them cannot be
  // crossed, and no transition may be read at them.
  TurnedFan t(3);
  t.layers.branch[0] = t.layers.branch[1] = 1;
  for (int f = 0; f < t.mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c)
      if (t.mesh.F()(f, c) <= 1) t.layers.layer(f, c) = 2;
  const Eigen::VectorXcd zero = Eigen::VectorXcd::Zero(t.mesh.num_vertices());
  const auto around = developed_around(t.mesh, t.layers, t.base, zero, 0, 2);
  // The walk from face 0 goes around the other way and still reaches all faces.
  EXPECT_EQ(around.size(), 3u * t.mesh.num_faces());
  for (const auto& [v, z] : around) EXPECT_LT(std::abs(z - flat(t.mesh, v)), 1e-12) << v;
}

}  // namespace
}  // namespace quadcover
