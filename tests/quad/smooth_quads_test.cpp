// Tangential smoothing of extracted quad meshes: exact grids are fixed points, perturbed grids relax back, and on
// real meshes the result stays on the surface, keeps its connectivity and evens out edge lengths and angles.
#include "quad/smooth_quads.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "common/errors.h"
#include "field/compute_frame_field.h"
#include "mesh/triangle_tree.h"
#include "param/parameterize.h"
#include "quad/extract_quads.h"
#include "quad/quad_test_maps.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

double rsd(const std::vector<double>& x) {
  double mean = 0, var = 0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  for (double v : x) var += (v - mean) * (v - mean);
  return 100 * std::sqrt(var / static_cast<double>(x.size())) / mean;
}

// RSD (percent) of the quads' edge lengths (each edge once per quad side) and of their corner angles.
std::pair<double, double> quad_rsd(const QuadMesh& q) {
  std::vector<double> lengths, angles;
  for (const auto& f : q.faces) {
    if (f.size() != 4) continue;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p = q.V.row(f[k]), next = q.V.row(f[(k + 1) % 4]), prev = q.V.row(f[(k + 3) % 4]);
      lengths.push_back((next - p).norm());
      angles.push_back(std::acos(std::clamp((next - p).normalized().dot((prev - p).normalized()), -1.0, 1.0)));
    }
  }
  return {rsd(lengths), rsd(angles)};
}

// Corners of quads that turn against the normal of the input triangle under their vertex.
int inverted_corners(const QuadMesh& q, const Mesh& mesh) {
  int bad = 0;
  for (const auto& f : q.faces) {
    if (f.size() != 4) continue;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p = q.V.row(f[k]), next = q.V.row(f[(k + 1) % 4]), prev = q.V.row(f[(k + 3) % 4]);
      bad += (next - p).cross(prev - p).dot(mesh.face_normals().row(q.source_face[f[k]])) <= 0;
    }
  }
  return bad;
}

TEST(SmoothQuads, ExactGridIsAFixedPoint) {
  const auto [mesh, param] = testing::square_map(4, 6.0, 0.0, {0, 0});  // 6 × 6 squares of side 1/6
  const QuadMesh extracted = extract_quads(mesh, param).mesh;
  ASSERT_EQ(extracted.num_faces(), 36);
  for (double rigidity : {0.0, 0.5, 1.0}) {
    QuadMesh q = extracted;
    QuadSmoothingOptions o;
    o.rigidity = rigidity;
    const QuadSmoothingReport r = smooth_quads(q, mesh, param, o);
    EXPECT_EQ(r.iterations, o.iterations);
    EXPECT_NEAR(r.edge_length, 1.0 / 6, 1e-12);
    EXPECT_EQ(r.fixed_vertices, 24);  // the boundary of the 7 × 7 grid
    EXPECT_EQ(r.rejected_moves, 0);
    EXPECT_LT((q.V - extracted.V).cwiseAbs().maxCoeff(), 1e-12) << "rigidity " << rigidity;
    EXPECT_LT(r.max_displacement, 1e-10);
  }
}

TEST(SmoothQuads, PerturbedGridRelaxesBackAndUpdatesTheMap) {
  const auto [mesh, param] = testing::square_map(4, 6.0, 0.0, {0, 0});  // φ(p) = 6 p
  const QuadMesh grid = extract_quads(mesh, param).mesh;
  QuadMesh q = grid;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.2 / 6, 0.2 / 6);
  const TriangleTree tree(mesh.V(), mesh.F());
  for (int v = 0; v < q.num_vertices(); ++v) {
    const Eigen::Vector3d p = q.V.row(v);
    if (p.x() <= 1e-12 || p.y() <= 1e-12 || p.x() >= 1 - 1e-12 || p.y() >= 1 - 1e-12) continue;  // boundary
    q.V(v, 0) += jitter(rng);
    q.V(v, 1) += jitter(rng);
    int face = -1;
    tree.squared_distance(q.V.row(v).transpose(), &face);
    q.source_face[v] = face;
  }
  const double perturbed = quad_rsd(q).first;
  ASSERT_GT(perturbed, 5.0);
  QuadSmoothingOptions o;
  o.iterations = 300;
  o.rigidity = 1;  // the grid is the only state with every quad a square of side h and the boundary fixed
  const QuadSmoothingReport r = smooth_quads(q, mesh, param, o);
  EXPECT_EQ(q.faces, grid.faces);
  EXPECT_LT(quad_rsd(q).first, 0.05 * perturbed);
  for (int v = 0; v < q.num_vertices(); ++v) {
    EXPECT_EQ(q.V(v, 2), 0.0) << "vertex " << v << " left the plane";
    EXPECT_LT((q.V.row(v) - grid.V.row(v)).norm(), 0.05 / 6) << "vertex " << v;
    // uv is φ at the new point, in the chart of the new source face.
    EXPECT_LT(std::abs(q.uv[v] - 6.0 * Complex(q.V(v, 0), q.V(v, 1))), 1e-9) << "vertex " << v;
  }
  EXPECT_GT(r.mean_displacement, 0.0);
}

TEST(SmoothQuads, NoRoundsChangeNothing) {
  const Mesh mesh = testing::load_test_mesh("spot.obj");
  const Parameterization P = parameterize(mesh, compute_frame_field(mesh));
  QuadMesh q = extract_quads(mesh, P).mesh;
  const QuadMesh before = q;
  QuadSmoothingOptions o;
  o.iterations = 0;
  const QuadSmoothingReport r = smooth_quads(q, mesh, P, o);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(q.V, before.V);
  EXPECT_EQ(q.uv, before.uv);
}

TEST(SmoothQuads, RefusesAQuadMeshWithoutSourceFaces) {
  const auto [mesh, param] = testing::square_map(4, 6.0, 0.0, {0, 0});
  QuadMesh q = extract_quads(mesh, param).mesh;
  q.source_face.resize(0);
  EXPECT_THROW(smooth_quads(q, mesh, param, {}), InputError);
}

class SmoothShipped : public ::testing::TestWithParam<const char*> {};

TEST_P(SmoothShipped, StaysOnTheSurfaceAndEvensOutTheQuads) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  const Parameterization P = parameterize(mesh, compute_frame_field(mesh));
  const QuadMesh extracted = extract_quads(mesh, P).mesh;
  QuadMesh q = extracted, again = extracted;
  const QuadSmoothingReport r = smooth_quads(q, mesh, P, {});
  smooth_quads(again, mesh, P, {});
  EXPECT_EQ(q.V, again.V) << "not deterministic";
  EXPECT_EQ(q.faces, extracted.faces);
  EXPECT_EQ(r.iterations, QuadSmoothingOptions{}.iterations);

  const auto [edge_before, angle_before] = quad_rsd(extracted);
  const auto [edge_after, angle_after] = quad_rsd(q);
  EXPECT_LT(edge_after, edge_before);
  EXPECT_LT(angle_after, angle_before);
  EXPECT_LE(inverted_corners(q, mesh), inverted_corners(extracted, mesh));

  const TriangleTree tree(mesh.V(), mesh.F());
  const double diagonal = mesh.bounding_box_diagonal();
  std::vector<char> on_boundary(q.num_vertices(), 0), in_polygon(q.num_vertices(), 0);
  {
    std::map<std::pair<int, int>, int> count;
    for (const auto& f : q.faces)
      for (std::size_t k = 0; k < f.size(); ++k) ++count[std::minmax(f[k], f[(k + 1) % f.size()])];
    for (const auto& [e, c] : count)
      if (c == 1) on_boundary[e.first] = on_boundary[e.second] = 1;
    for (const auto& f : q.faces)
      if (f.size() != 4)
        for (int v : f) in_polygon[v] = 1;
  }
  for (int v = 0; v < q.num_vertices(); ++v) {
    int face = -1;
    EXPECT_LT(std::sqrt(tree.squared_distance(q.V.row(v).transpose(), &face)), 1e-9 * diagonal) << "vertex " << v;
    if (on_boundary[v] || in_polygon[v]) {
      EXPECT_EQ(q.V.row(v), extracted.V.row(v)) << "fixed vertex " << v << " moved";
      EXPECT_EQ(q.uv[v], extracted.uv[v]);
    }
  }
  EXPECT_LT(r.max_displacement, 3.0);
}

INSTANTIATE_TEST_SUITE_P(Meshes, SmoothShipped,
                         ::testing::Values("bunny_3k.obj", "camelhead_boundary.obj", "fandisk.obj",
                                           "eight_genus2.obj"));

}  // namespace
}  // namespace quadcover
