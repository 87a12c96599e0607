// The disk around a wrongly wound branch point laid out again in its cone chart (param/cone_disk_layout.h), on a
// polar grid around a −1/4 cone (angle 5π/2) whose inner rings wind π/2 while the rim winds 5π/2.
#include "param/cone_disk_layout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <numbers>

#include "common/progress.h"
#include "param/ring_winding.h"
#include "param/seams.h"
#include "param/untangle.h"

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
  // The last: a rim 12 rings out, where a coarse map of a dense mesh puts it (igea_270k: 7-8 rings).
  for (const auto& [n, rings] : {std::pair{8, 3}, std::pair{12, 4}, std::pair{7, 5}, std::pair{8, 12}}) {
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

TEST(ConeDiskLayout, NoDiskOfMoreThanTheFaceCap) {
  const int n = 200, rings = 12;  // the rim's disk has n + 2n(rings − 1) = 4600 faces
  ASSERT_GT(static_cast<std::size_t>(n + 2 * n * (rings - 1)), kMaxConeDiskFaces);
  const WoundCone w = make_wound_cone(n, rings);
  Eigen::VectorXcd u = Eigen::VectorXcd::Zero(w.nv());
  EXPECT_TRUE(lay_out_cone_disk(w.grid.mesh, w.map.layers, w.map.base, w.fixed, 5 * kPi / 2, 0, u).empty());
  EXPECT_EQ(u, Eigen::VectorXcd::Zero(w.nv()));
  const WoundCone small = make_wound_cone(20, rings);  // 460 faces: laid out
  u = Eigen::VectorXcd::Zero(small.nv());
  EXPECT_FALSE(
      lay_out_cone_disk(small.grid.mesh, small.map.layers, small.map.base, small.fixed, 5 * kPi / 2, 0, u).empty());
}

/// F_0 = Σ_t A_t f_0(J_t) (param/untangle.h) recomputed from the map: J maps the face's 3D triangle, in any
/// orthonormal frame of its plane, onto its parameter triangle (the reference Z is the identity).
double barrier_energy(const Mesh& mesh, const Eigen::MatrixX3cd& uv) {
  double E = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d p0 = mesh.V().row(mesh.F()(f, 0)), p1 = mesh.V().row(mesh.F()(f, 1)),
                          p2 = mesh.V().row(mesh.F()(f, 2));
    const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0, x = e1.normalized(), y = (e2 - e2.dot(x) * x).normalized();
    Eigen::Matrix2d S, P;  // columns: the edges in the plane and in the map
    S << e1.dot(x), e2.dot(x), e1.dot(y), e2.dot(y);
    const Complex d1 = uv(f, 1) - uv(f, 0), d2 = uv(f, 2) - uv(f, 0);
    P << d1.real(), d2.real(), d1.imag(), d2.imag();
    E += 0.5 * std::abs(S.determinant()) * untangle_density(P * S.inverse(), 0, 1.0);
  }
  return E;
}

TEST(ConeDiskLayout, PolishLowersTheBarrierInsideTheDiskAndKeepsItsWinding) {
  const WoundCone w = make_wound_cone(9, 5);
  const Mesh& mesh = w.grid.mesh;
  const ConeMap& m = w.map;
  const int nf = mesh.num_faces();
  FramePairs Z(nf, 2);
  Z.col(0).setConstant(Complex(1, 0));
  Z.col(1).setConstant(Complex(0, 1));
  const Eigen::VectorXcd wound = Eigen::VectorXcd::Zero(w.nv());
  ASSERT_GT(flipped_triangles(mesh, m.base - layered_values(mesh, m.layers, wound)).non_positive, 0);
  ParamDiagnostics::Untangling r;
  const std::vector<int> everything = [&] {
    std::vector<int> all(static_cast<std::size_t>(w.nv()));
    for (int v = 0; v < w.nv(); ++v) all[static_cast<std::size_t>(v)] = v;
    return all;
  }();
  // A folded map is not polished: the barrier is infinite there.
  EXPECT_EQ(polish_map(mesh, m.layers, m.base, Z, w.fixed, wound, everything, {}, null_progress(), r), wound);
  Eigen::VectorXcd laid = wound;
  const std::vector<int> disk = lay_out_cone_disk(mesh, m.layers, m.base, w.fixed, 5 * kPi / 2, 0, laid);
  ASSERT_FALSE(disk.empty());
  const Eigen::MatrixX3cd before = m.base - layered_values(mesh, m.layers, laid);
  ASSERT_EQ(flipped_triangles(mesh, before).non_positive, 0);
  const Eigen::VectorXcd polished = polish_map(mesh, m.layers, m.base, Z, w.fixed, laid, disk, {}, null_progress(), r);
  const Eigen::MatrixX3cd after = m.base - layered_values(mesh, m.layers, polished);
  EXPECT_GT(r.polish_iterations, 0);
  EXPECT_LT(barrier_energy(mesh, after), barrier_energy(mesh, before));
  EXPECT_EQ(flipped_triangles(mesh, after).non_positive, 0);
  EXPECT_NEAR(fan_angle(mesh, m.layers, m.base, polished, 0), 5 * kPi / 2, 1e-9);
  const Eigen::VectorXi q = map_quarter_index(mesh, after);
  for (int v = 1; v < w.nv(); ++v) EXPECT_EQ(q[v], 0) << v;
  std::vector<char> in_disk(static_cast<std::size_t>(w.nv()), 0);
  for (int v : disk) in_disk[static_cast<std::size_t>(v)] = 1;
  for (int v = 0; v < w.nv(); ++v) {  // the rim and the cone stay
    if (!in_disk[static_cast<std::size_t>(v)]) {
      EXPECT_EQ(polished[v], laid[v]) << v;
    }
  }
}

}  // namespace
}  // namespace quadcover
