// Tangential smoothing of extracted quad meshes: exact grids are fixed points, perturbed grids relax back, and on
// real meshes the result stays on the surface, keeps its connectivity and evens out edge lengths and angles.
#include "quad/smooth_quads.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include "common/errors.h"
#include "field/compute_frame_field.h"
#include "field/feature_alignment.h"
#include "mesh/segment_grid.h"
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

// The input's normal at a quad vertex: its source triangle's, or on an input edge (a crease) the mean of both sides'.
Eigen::Vector3d normal_at(const QuadMesh& q, const Mesh& mesh, int v) {
  const int t = q.source_face[v];
  const Eigen::Vector3d p = q.V.row(v);
  Eigen::Vector3d n = mesh.face_normals().row(t);
  for (int k = 0; k < 3; ++k) {
    const int e = mesh.FE()(t, k), other = mesh.EF()(e, 0) == t ? mesh.EF()(e, 1) : mesh.EF()(e, 0);
    if (other < 0) continue;
    const Eigen::Vector3d a = mesh.V().row(mesh.E()(e, 0)), b = mesh.V().row(mesh.E()(e, 1));
    if ((closest_point_on_segment(p, a, b) - p).norm() <= 1e-9 * (b - a).norm())
      n += mesh.face_normals().row(other).transpose();
  }
  return n.normalized();
}

// Corners of quads that turn against the input's normal at their vertex.
int inverted_corners(const QuadMesh& q, const Mesh& mesh) {
  int bad = 0;
  for (const auto& f : q.faces) {
    if (f.size() != 4) continue;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p = q.V.row(f[k]), next = q.V.row(f[(k + 1) % 4]), prev = q.V.row(f[(k + 3) % 4]);
      bad += (next - p).cross(prev - p).dot(normal_at(q, mesh, f[k])) <= 0;
    }
  }
  return bad;
}

// Share of the input's sharp feature edges whose midpoint is within 0.1 h of an edge of q (1 without features).
double sharp_edges_covered(const QuadMesh& q, const Mesh& mesh, double h) {
  std::set<std::pair<int, int>> edges;
  for (const auto& f : q.faces)
    for (std::size_t k = 0; k < f.size(); ++k) edges.insert(std::minmax(f[k], f[(k + 1) % f.size()]));
  Eigen::MatrixX2i E(static_cast<Eigen::Index>(edges.size()), 2);
  int i = 0;
  for (const auto& [a, b] : edges) E.row(i++) << a, b;
  const SegmentGrid grid(q.V, E);
  const std::vector<int> sharp = feature_constraints(mesh).feature_edges;
  int covered = 0;
  for (int e : sharp) {
    const Eigen::Vector3d mid = 0.5 * (mesh.V().row(mesh.E()(e, 0)) + mesh.V().row(mesh.E()(e, 1))).transpose();
    covered += grid.squared_distance(mid) <= 0.01 * h * h;
  }
  return sharp.empty() ? 1.0 : static_cast<double>(covered) / static_cast<double>(sharp.size());
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
    EXPECT_EQ(r.fixed_vertices, 4);      // the corners of the 7 × 7 grid
    EXPECT_EQ(r.boundary_vertices, 20);  // the rest of its boundary slides (and stays: the grid is square)
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

// make_grid(20) folded up by 60° along x = 0.5 (a sharp crease of 20 edges), with φ = 6 p + 0.2 of the unfolded p:
// the integer line Re φ = 3 runs at x = 0.4667, 0.2 h beside the crease.
testing::MeshAndMap folded_square_map() {
  const Mesh grid = testing::make_grid(20);
  Eigen::MatrixX3d V = grid.V();
  for (int v = 0; v < V.rows(); ++v)
    if (V(v, 0) > 0.5) {
      const double t = V(v, 0) - 0.5;
      V.row(v) << 0.5 + t * std::cos(std::numbers::pi / 3), V(v, 1), t * std::sin(std::numbers::pi / 3);
    }
  testing::MeshAndMap r{Mesh::from_triangles(V, grid.F()), {}};
  Eigen::MatrixX3cd uv(grid.num_faces(), 3);
  for (int f = 0; f < grid.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const auto p = grid.V().row(grid.F()(f, c));
      uv(f, c) = 6.0 * Complex(p.x(), p.y()) + 0.2;
    }
  r.param = parameterization_from_uv(r.mesh, uv);
  return r;
}

TEST(SmoothQuads, VerticesNearACreaseSnapOntoItAndSlideAlongIt) {
  const auto [mesh, param] = folded_square_map();
  const QuadMesh extracted = extract_quads(mesh, param).mesh;
  // The interior vertices of the line Re φ = 3 (x = 0.4667 unfolded), 5 of them.
  std::vector<int> row;
  for (int v = 0; v < extracted.num_vertices(); ++v)
    if (extracted.on_grid[v] && std::abs(extracted.uv[v].real() - 3) < 1e-9 && extracted.V(v, 1) > 1e-9 &&
        extracted.V(v, 1) < 1 - 1e-9)
      row.push_back(v);
  ASSERT_EQ(row.size(), 5u);
  QuadMesh q = extracted;
  const QuadSmoothingReport r = smooth_quads(q, mesh, param, {});
  EXPECT_EQ(r.feature_vertices, 5);  // the next line, 0.8 h away on the other side, stays free
  for (int v : row) {
    EXPECT_NEAR(q.V(v, 0), 0.5, 1e-9) << "vertex " << v << " is not on the crease";
    EXPECT_NEAR(q.V(v, 2), 0.0, 1e-9);
    EXPECT_NEAR(q.uv[v].real(), 3.2, 1e-9);  // φ at the crease point
    EXPECT_NEAR(q.uv[v].imag(), 6 * q.V(v, 1), 1e-9);
  }
  EXPECT_EQ(inverted_corners(q, mesh), 0);
  EXPECT_EQ(q.faces, extracted.faces);
  // Off: vertices near the crease are smoothed like the others and do not reach it.
  QuadMesh off = extracted;
  QuadSmoothingOptions o;
  o.feature_snap = 0;
  EXPECT_EQ(smooth_quads(off, mesh, param, o).feature_vertices, 0);
  for (int v : row) EXPECT_GT(std::abs(off.V(v, 0) - 0.5), 0.01);
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

  // Without feature sliding the quads even out; sliding trades some of that for quad edges on the creases.
  QuadMesh plain = extracted;
  QuadSmoothingOptions no_snap;
  no_snap.feature_snap = 0;
  smooth_quads(plain, mesh, P, no_snap);
  const auto [edge_before, angle_before] = quad_rsd(extracted);
  const auto [edge_plain, angle_plain] = quad_rsd(plain);
  const auto [edge_after, angle_after] = quad_rsd(q);
  EXPECT_LT(edge_plain, edge_before);
  EXPECT_LT(angle_plain, angle_before);
  EXPECT_LT(edge_after, 1.1 * edge_before);
  EXPECT_LT(angle_after, 1.1 * angle_before);
  EXPECT_LE(inverted_corners(q, mesh), inverted_corners(extracted, mesh));
  EXPECT_LE(inverted_corners(plain, mesh), inverted_corners(extracted, mesh));
  const double covered = sharp_edges_covered(q, mesh, r.edge_length),
               before = sharp_edges_covered(extracted, mesh, r.edge_length);
  EXPECT_GE(covered, before);
  EXPECT_GE(covered, sharp_edges_covered(plain, mesh, r.edge_length));
  if (r.feature_vertices > 0) {
    EXPECT_GT(covered, before);
  }

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
  // Boundary vertices slide along the input's boundary; with slide_boundary off they stay, as corners of polygons do.
  QuadMesh held = extracted;
  QuadSmoothingOptions no_slide;
  no_slide.slide_boundary = false;
  const QuadSmoothingReport rh = smooth_quads(held, mesh, P, no_slide);
  EXPECT_EQ(rh.boundary_vertices, 0);
  EXPECT_EQ(r.boundary_vertices > 0, mesh.num_boundary_loops() > 0);
  const SegmentGrid boundary(mesh.V(), mesh.edge_endpoints(mesh.boundary_edges()));
  for (int v = 0; v < q.num_vertices(); ++v) {
    int face = -1;
    EXPECT_LT(std::sqrt(tree.squared_distance(q.V.row(v).transpose(), &face)), 1e-9 * diagonal) << "vertex " << v;
    if (on_boundary[v]) {
      EXPECT_LT(std::sqrt(boundary.squared_distance(q.V.row(v).transpose())), 1e-9 * diagonal) << "vertex " << v;
    }
    if (on_boundary[v] || in_polygon[v]) {
      EXPECT_EQ(held.V.row(v), extracted.V.row(v)) << "fixed vertex " << v << " moved";
      EXPECT_EQ(held.uv[v], extracted.uv[v]);
    }
    if (in_polygon[v]) {
      EXPECT_EQ(q.V.row(v), extracted.V.row(v)) << "polygon corner " << v << " moved";
    }
  }
  EXPECT_LT(r.max_displacement, 3.0);
}

// The boundary quads of a rotated square (clipped cells made quads, quad/quadrangulate.h): sliding the boundary
// vertices along the square's sides squares them up better than holding them, and no vertex leaves a side or
// rounds a corner of the square.
TEST(SmoothQuads, BoundaryVerticesSlideAlongTheBoundary) {
  const auto [mesh, param] = testing::square_map(5, 7.3, 0.4, {0.21, 0.13});
  const QuadMesh extracted = extract_quads(mesh, param).mesh;
  QuadMesh slid = extracted, held = extracted;
  const QuadSmoothingReport r = smooth_quads(slid, mesh, param, {});
  QuadSmoothingOptions no_slide;
  no_slide.slide_boundary = false;
  smooth_quads(held, mesh, param, no_slide);
  EXPECT_GT(r.boundary_vertices, 10);
  EXPECT_LT(quad_rsd(slid).second, quad_rsd(held).second);
  const std::vector<char> on_boundary = quad_boundary_vertices(slid);
  for (int v = 0; v < slid.num_vertices(); ++v) {
    if (!on_boundary[v]) continue;
    const Eigen::Vector3d p = slid.V.row(v), p0 = extracted.V.row(v);
    EXPECT_NEAR(std::min({p.x(), 1 - p.x(), p.y(), 1 - p.y()}), 0, 1e-12) << "vertex " << v;
    const auto side = [](const Eigen::Vector3d& x) {  // which side of the square (corners count as both)
      return std::array<bool, 4>{x.x() < 1e-12, x.x() > 1 - 1e-12, x.y() < 1e-12, x.y() > 1 - 1e-12};
    };
    const auto s = side(p), s0 = side(p0);
    bool shared = false;
    for (int k = 0; k < 4; ++k) shared |= s[k] && s0[k];
    EXPECT_TRUE(shared) << "vertex " << v << " went round a corner";
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, SmoothShipped,
                         ::testing::Values("bunny_3k.obj", "camelhead_boundary.obj", "fandisk.obj",
                                           "eight_genus2.obj"));

}  // namespace
}  // namespace quadcover
