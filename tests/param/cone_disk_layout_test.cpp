// The disk around a wrongly wound branch point laid out again in its cone chart (param/cone_disk_layout.h), on a
// polar grid around a −1/4 cone (angle 5π/2) whose inner rings wind π/2 while the rim winds 5π/2.
#include "param/cone_disk_layout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "param/ring_winding.h"

namespace quadcover {
namespace {

constexpr double kPi = std::numbers::pi;

/// A polar grid: the centre 0, then `rings` rings of n vertices (ring r, index j: 1 + (r − 1)·n + j); the faces
/// between angles j and j + 1 (mod n) wrap where j = n − 1.
struct PolarGrid {
  int n, rings;
  Mesh mesh;
  int vertex(int r, int j) const { return r == 0 ? 0 : 1 + (r - 1) * n + (j % n); }
};

PolarGrid make_polar_grid(int n, int rings) {
  PolarGrid g{n, rings, {}};
  Eigen::MatrixX3d V(1 + n * rings, 3);
  V.row(0).setZero();
  for (int r = 1; r <= rings; ++r)
    for (int j = 0; j < n; ++j)
      V.row(g.vertex(r, j)) << r * std::cos(2 * kPi * j / n), r * std::sin(2 * kPi * j / n), 0;
  std::vector<Eigen::Vector3i> faces;
  for (int j = 0; j < n; ++j) faces.emplace_back(0, g.vertex(1, j), g.vertex(1, j + 1));
  for (int r = 1; r < rings; ++r)
    for (int j = 0; j < n; ++j) {
      faces.emplace_back(g.vertex(r, j), g.vertex(r + 1, j), g.vertex(r + 1, j + 1));
      faces.emplace_back(g.vertex(r, j), g.vertex(r + 1, j + 1), g.vertex(r, j + 1));
    }
  Eigen::MatrixX3i F(static_cast<int>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) F.row(static_cast<int>(f)) = faces[f].transpose();
  g.mesh = Mesh::from_triangles(V, F);
  return g;
}

/// The seamless map of the grid with the centre a branch point of angle 5π/2 on 0: vertex (r, j) at
/// r·e^{i·sweep(r)·j/n}, sweep(r) = π/2 for the inner rings (wound a turn short) and 5π/2 for the rim; in the faces
/// that wrap, the vertices of angle index 0 are seen through the transition i (layer 1), at r·e^{i·sweep(r)}.
struct ConeMap {
  VertexLayers layers;
  Eigen::MatrixX3cd base;
};

ConeMap wound_cone_map(const PolarGrid& g) {
  const Mesh& mesh = g.mesh;
  ConeMap m{{Eigen::MatrixX3i::Zero(mesh.num_faces(), 3), Eigen::VectorXi::Zero(mesh.num_vertices())},
            Eigen::MatrixX3cd::Zero(mesh.num_faces(), 3)};
  m.layers.branch[0] = 1;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    bool wraps = false;  // a corner of angle index n − 1 and one of index 0
    for (int c = 0; c < 3; ++c) wraps = wraps || (mesh.F()(f, c) > 0 && (mesh.F()(f, c) - 1) % g.n == g.n - 1);
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.F()(f, c);
      if (v == 0) continue;
      const int r = 1 + (v - 1) / g.n, j = (v - 1) % g.n;
      const double sweep = r == g.rings ? 5 * kPi / 2 : kPi / 2;
      const bool turned = wraps && j == 0;
      m.layers.layer(f, c) = turned ? 1 : 0;
      m.base(f, c) = std::polar(static_cast<double>(r), sweep * (turned ? g.n : j) / g.n);
    }
  }
  return m;
}

/// The grid, its wound map and the held components (the centre, held on its lattice point).
struct WoundCone {
  PolarGrid grid;
  ConeMap map;
  std::vector<char> fixed;
  int nv() const { return grid.mesh.num_vertices(); }
};

WoundCone make_wound_cone(int n, int rings) {
  WoundCone w{make_polar_grid(n, rings), {}, {}};
  w.map = wound_cone_map(w.grid);
  w.fixed.assign(static_cast<std::size_t>(2 * w.nv()), 0);
  w.fixed[0] = w.fixed[w.nv()] = 1;
  return w;
}

TEST(ConeDiskLayout, ADiskWhoseRimSweepsTheConeAngleIsLaidOutAgainWithTheConesWinding) {
  for (const auto& [n, rings] : {std::pair{8, 3}, std::pair{12, 4}, std::pair{7, 5}}) {
    SCOPED_TRACE(n);
    const WoundCone w = make_wound_cone(n, rings);
    const PolarGrid& g = w.grid;
    const ConeMap& m = w.map;
    const int nv = w.nv();
    const Eigen::VectorXcd u0 = Eigen::VectorXcd::Zero(nv);
    ASSERT_NEAR(fan_angle(g.mesh, m.layers, m.base, u0, 0), kPi / 2, 1e-9);  // a turn short
    Eigen::VectorXcd u = u0;
    const std::vector<int> moved = lay_out_cone_disk(g.mesh, m.layers, m.base, w.fixed, 5 * kPi / 2, 0, u);
    ASSERT_EQ(static_cast<int>(moved.size()), n * (rings - 1));  // every ring inside the rim
    EXPECT_NEAR(fan_angle(g.mesh, m.layers, m.base, u, 0), 5 * kPi / 2, 1e-9);
    const Eigen::MatrixX3cd uv = m.base - layered_values(g.mesh, m.layers, u);
    const Eigen::VectorXi wound = map_quarter_index(g.mesh, uv);
    for (int v = 1; v < nv; ++v)
      if (!g.mesh.is_boundary_vertex(v)) {
        EXPECT_EQ(wound[v], 0) << v;
      }                                                                // every other interior vertex at 2π
    for (int f = 0; f < g.mesh.num_faces(); ++f) {                     // symmetric: the layout is an embedding
      const Complex e1 = uv(f, 1) - uv(f, 0), e2 = uv(f, 2) - uv(f, 0);
      EXPECT_GT(std::imag(std::conj(e1) * e2), 0) << f;
    }
    for (int j = 0; j < n; ++j) EXPECT_EQ(u[g.vertex(rings, j)], Complex(0)) << j;  // the rim stays
  }
}

TEST(ConeDiskLayout, NoDiskWithAnotherBranchPointOrAHeldVertexInsideAndTheMapStays) {
  WoundCone w = make_wound_cone(8, 3);
  const PolarGrid& g = w.grid;
  const ConeMap& m = w.map;
  const int nv = w.nv();
  std::vector<char>& fixed = w.fixed;
  fixed[g.vertex(1, 3)] = 1;  // one component of a ring vertex held (a curve constraint)
  const Eigen::VectorXcd u0 = Eigen::VectorXcd::Zero(nv);
  Eigen::VectorXcd u = u0;
  EXPECT_TRUE(lay_out_cone_disk(g.mesh, m.layers, m.base, fixed, 5 * kPi / 2, 0, u).empty());
  EXPECT_EQ(u, u0);
  fixed[g.vertex(1, 3)] = 0;
  ConeMap two = m;  // another branch point inside
  two.layers.branch[g.vertex(1, 3)] = 1;
  EXPECT_TRUE(lay_out_cone_disk(g.mesh, two.layers, two.base, fixed, 5 * kPi / 2, 0, u).empty());
  EXPECT_EQ(u, u0);
  // The rim sweeps 5π/2, but a cone of angle 9π/2 asks for two more turns: no disk sweeps that.
  EXPECT_TRUE(lay_out_cone_disk(g.mesh, m.layers, m.base, fixed, 9 * kPi / 2, 0, u).empty());
  EXPECT_EQ(u, u0);
  // Without them the same disk is laid out.
  EXPECT_FALSE(lay_out_cone_disk(g.mesh, m.layers, m.base, fixed, 5 * kPi / 2, 0, u).empty());
}

TEST(ConeDiskLayout, RewindRingsLaysOutTheDiskOfAWronglyWoundBranchPointFirst) {
  const WoundCone w = make_wound_cone(10, 4);
  const PolarGrid& g = w.grid;
  const ConeMap& m = w.map;
  const int nv = w.nv();
  Eigen::VectorXi target = Eigen::VectorXi::Zero(nv);
  target[0] = -1;
  RingRewinding out;
  const Eigen::VectorXcd u = rewind_rings(g.mesh, m.layers, m.base, Eigen::VectorXcd::Zero(nv), w.fixed, target, out);
  EXPECT_EQ(out.disks, std::vector<int>{0});
  EXPECT_EQ(out.rewound, std::vector<int>{0});
  EXPECT_TRUE(out.moved.empty());  // nothing to hold: the disk's rim did not move
  const Eigen::VectorXi wound = map_quarter_index(g.mesh, m.base - layered_values(g.mesh, m.layers, u));
  for (int v = 0; v < nv; ++v)
    if (!g.mesh.is_boundary_vertex(v)) {
      EXPECT_EQ(wound[v], target[v]) << v;
    }
}

}  // namespace
}  // namespace quadcover
