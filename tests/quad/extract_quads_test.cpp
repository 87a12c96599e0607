// Quad extraction on integer-grid maps whose quad meshes are known exactly.
#include "quad/extract_quads.h"

#include <gtest/gtest.h>

#include <random>

#include "common/errors.h"
#include "quad/integer_grid_map.h"
#include "mesh/surface_counts.h"
#include "param/face_count.h"
#include "quad/polygon_check.h"
#include "quad/quad_test_maps.h"
#include "quad/repair_folds.h"

namespace quadcover {
namespace {

using testing::cube_map;
using testing::square_map;
using testing::torus_map;

std::vector<int> valences(const QuadMesh& q) {
  std::vector<int> val(q.num_vertices(), 0);
  for (const auto& f : q.faces)
    for (int v : f) ++val[v];  // faces per vertex = valence on a closed manifold
  return val;
}

void expect_clean(const ExtractionReport& r) {
  EXPECT_EQ(r.flipped_triangles, 0);
  EXPECT_EQ(r.torn_seams, 0);
  EXPECT_EQ(r.failed_traces, 0);
  EXPECT_EQ(r.dropped_faces, 0);
  EXPECT_EQ(r.degenerate_faces, 0);
}

struct TorusCase {
  int nM, nm, P, Q, shear;
  double x0, y0;
};
class TorusMaps : public ::testing::TestWithParam<TorusCase> {};

// A torus map with periods (P, 0) and (shear, Q) covers P·Q unit cells: exactly P·Q regular quads.
TEST_P(TorusMaps, ExactQuadCountAllRegular) {
  const TorusCase c = GetParam();
  const auto [mesh, param] = torus_map(c.nM, c.nm, c.P, c.Q, c.shear, c.x0, c.y0);
  const ExtractionResult res = extract_quads(mesh, param);
  expect_clean(res.report);
  EXPECT_EQ(res.mesh.num_faces(), c.P * c.Q);
  EXPECT_EQ(res.mesh.num_quads(), c.P * c.Q);
  EXPECT_EQ(res.mesh.num_vertices(), c.P * c.Q);
  EXPECT_NEAR(parameter_area(mesh, param.uv), res.mesh.num_quads(), 1e-6);
  const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_TRUE(t.manifold() && t.oriented());
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.euler_characteristic, 0);
  for (int v : valences(res.mesh)) EXPECT_EQ(v, 4);
  for (int i = 0; i < res.mesh.num_vertices(); ++i) {
    EXPECT_EQ(res.mesh.on_grid[i], 1);
    EXPECT_DOUBLE_EQ(res.mesh.uv[i].real(), std::round(res.mesh.uv[i].real()));
  }
}
INSTANTIATE_TEST_SUITE_P(
    Cases, TorusMaps,
    ::testing::Values(TorusCase{24, 12, 17, 7, 0, 0.31, 0.17},    // generic: lines cross triangles
                      TorusCase{24, 12, 24, 12, 0, 0.0, 0.0},     // grid points on every mesh vertex, lines on edges
                      TorusCase{24, 12, 12, 6, 0, 0.0, 0.5},      // lines through vertices and along edges
                      TorusCase{30, 10, 9, 5, 2, 0.43, 0.05},     // sheared periods
                      TorusCase{16, 8, 3, 2, 1, 0.5, 0.5},        // coarse: quads much larger than triangles
                      TorusCase{6, 4, 40, 30, 0, 0.123, 0.456}));  // fine: many grid points per triangle

// Cube surface: rotational seams (i^k) and eight valence-3 branch points at grid points.
TEST(ExtractQuads, CubeWithBranchPointsAtGridPoints) {
  for (const auto& [n, m] : {std::pair{3, 5}, std::pair{4, 4}, std::pair{2, 7}}) {
    const auto [mesh, param] = cube_map(n, m);
    const ExtractionResult res = extract_quads(mesh, param);
    expect_clean(res.report);
    EXPECT_EQ(res.mesh.num_quads(), 6 * m * m);
    EXPECT_EQ(res.mesh.num_faces(), 6 * m * m);
    EXPECT_EQ(res.mesh.num_vertices(), 6 * m * m + 2);
    const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
    EXPECT_TRUE((t.manifold() && t.oriented()) && t.closed());
    EXPECT_EQ(t.euler_characteristic, 2);
    const auto val = valences(res.mesh);
    EXPECT_EQ(std::count(val.begin(), val.end(), 3), 8);
    EXPECT_EQ(std::count(val.begin(), val.end(), 4), res.mesh.num_vertices() - 8);
  }
}

// Branch points at cell centres (plain Z[i] rounding, thesis 4.2.2 Fig. 4.4 left): each becomes a triangle.
TEST(ExtractQuads, CubeWithBranchPointsAtCellCentresGivesTriangles) {
  const int m = 5;
  const auto [mesh, param] = cube_map(3, m, {0.5, 0.5});
  const ExtractionResult res = extract_quads(mesh, param);
  expect_clean(res.report);
  EXPECT_EQ(res.mesh.num_quads(), 6 * m * m - 6);  // the 8 triangles cover 8 · ¾ of the area
  EXPECT_EQ(res.report.non_quads, 8);
  for (const auto& f : res.mesh.faces) EXPECT_TRUE(f.size() == 4 || f.size() == 3);
  const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_TRUE((t.manifold() && t.oriented()) && t.closed());
  EXPECT_EQ(t.euler_characteristic, 2);
}

// Round-off on the corner values (as a solver produces) must not change anything: predicates are exact after
// snapping and seam reconciliation.
TEST(ExtractQuads, RobustToRoundOffInCornerValues) {
  auto [mesh, param] = cube_map(3, 5);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-1e-9, 1e-9);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) param.uv(f, c) += Complex(noise(rng), noise(rng));
  const ExtractionResult res = extract_quads(mesh, param);
  expect_clean(res.report);
  EXPECT_EQ(res.mesh.num_quads(), 150);
  EXPECT_EQ(res.mesh.num_faces(), 150);
}

// A strip of sliver triangles across an iso-line: rows 5 and 6 of a 24 × 12 torus map 8e-7 grid units apart, on
// either side of y = 3. The map is injective (every triangle positive); snapping the rows onto the line would
// flatten the strip, and the collapse of near-zero edges would remove it: neither may happen, and the quads are
// the exact 17 × 7 grid.
TEST(ExtractQuads, KeepsASliverStripAcrossAnIsoLine) {
  const int nM = 24, nm = 12, P = 17, Q = 7;
  const double gap = 4e-7;
  const auto row_y = [&](int j) {  // rows 0..5 spread over [0.2, 3 - gap], rows 6..12 over [3 + gap, 7.2]
    const int jj = ((j % nm) + nm) % nm, wrap = (j - jj) / nm;
    const double y = jj <= 5 ? 0.2 + (3 - gap - 0.2) * jj / 5.0 : 3 + gap + (7.2 - 3 - gap) * (jj - 6) / 6.0;
    return y + Q * wrap;
  };
  const testing::MeshAndMap m =
      testing::torus_map_of(nM, nm, [&](int i, int j) { return Complex(P * double(i) / nM + 0.31, row_y(j)); });
  for (int f = 0; f < m.mesh.num_faces(); ++f) ASSERT_TRUE(grid::positive_in_map(m.param.uv.row(f))) << f;
  const grid::GridMap g = grid::build_grid_map(m.mesh, m.param, 1e-6, 1e-6);
  EXPECT_EQ(g.degenerate_faces + g.flipped_faces, 0);
  const ExtractionResult res = extract_quads(m.mesh, m.param);
  expect_clean(res.report);
  EXPECT_EQ(res.report.collapsed_edges, 0);
  EXPECT_EQ(res.report.degenerate_triangles, 0);
  EXPECT_EQ(res.report.unfolded_triangles, 0);
  EXPECT_EQ(res.report.filled_holes, 0);
  EXPECT_EQ(res.mesh.num_faces(), P * Q);
  EXPECT_EQ(res.mesh.num_quads(), P * Q);
  for (int v : valences(res.mesh)) EXPECT_EQ(v, 4);
}

// Aligned boundary: the unit square mapped onto [0,6]² gives the 6×6 grid.
TEST(ExtractQuads, SquareAlignedWithBoundary) {
  const auto [mesh, param] = square_map(4, 6.0, 0.0, {0, 0});
  const ExtractionResult res = extract_quads(mesh, param);
  expect_clean(res.report);
  EXPECT_EQ(res.mesh.num_quads(), 36);
  EXPECT_EQ(res.mesh.num_faces(), 36);
  EXPECT_EQ(res.mesh.num_vertices(), 49);
  const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_TRUE(t.manifold() && t.oriented());
  EXPECT_EQ(t.boundary_edges, 24);
  EXPECT_EQ(t.euler_characteristic, 1);
}

// A square whose top side runs at v = 5.9, with an ear triangle on it (two boundary edges) whose tip reaches v = 6.05
// between u = 3 and 4: the iso-line v = 6 cuts the ear's two boundary edges with no grid point between (as it cuts
// the teeth of a sawtooth boundary). The tip beyond it is a face of the two crossings alone: dropped and counted as
// a boundary sliver, not as a degenerate face (no map repair); the quad mesh stays a disk.
TEST(ExtractQuads, AnEarTipAcrossAnIsoLineIsABoundarySliverNotARepair) {
  const double scale = 5.9;
  const Complex offset(0.15, 0);
  const Mesh grid = testing::make_grid(4);
  const int left = 4 * 5 + 2, right = 4 * 5 + 3;  // (0.5, 1) and (0.75, 1): u = 3.1 and 4.575
  const Complex tip(3.5, 6.05);
  Eigen::MatrixX3d V(grid.num_vertices() + 1, 3);
  V << grid.V(), Eigen::RowVector3d((tip.real() - offset.real()) / scale, tip.imag() / scale, 0);
  Eigen::MatrixX3i F(grid.num_faces() + 1, 3);
  F << grid.F(), Eigen::RowVector3i(left, right, grid.num_vertices());
  const Mesh mesh = Mesh::from_triangles(V, F);
  ASSERT_EQ(mesh.boundary_loops().size(), 1u);
  Eigen::MatrixX3cd uv(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const auto p = mesh.V().row(mesh.F()(f, c));
      uv(f, c) = scale * Complex(p.x(), p.y()) + offset;
    }
  const ExtractionResult res = extract_quads(mesh, parameterization_from_uv(mesh, uv));
  EXPECT_EQ(res.report.boundary_slivers, 1);
  expect_clean(res.report);
  const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_TRUE(t.manifold() && t.oriented());
  EXPECT_EQ(t.euler_characteristic, 1);
  EXPECT_EQ(t.boundary_loops, 1);
}

// Polygon signed area in the parameter plane (all vertices of a face lie in one chart here: no seams).
double uv_area(const QuadMesh& q, const std::vector<int>& f) {
  double a = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const Complex p = q.uv[f[i]], r = q.uv[f[(i + 1) % f.size()]];
    a += 0.5 * (p.real() * r.imag() - p.imag() * r.real());
  }
  return a;
}

// A rotated square: faces cut by the boundary become clipped polygons; the polygons tile the parameter image
// except for the four corner triangles they cut off (each under half a cell).
TEST(ExtractQuads, RotatedSquareGivesClippedPolygons) {
  const double scale = 7.3, theta = 0.4;
  const auto [mesh, param] = square_map(5, scale, theta, {0.21, 0.13});
  ExtractOptions clipped;
  clipped.quadrangulate_boundary = false;
  const ExtractionResult res = extract_quads(mesh, param, clipped);
  expect_clean(res.report);
  const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_TRUE(t.manifold() && t.oriented());
  EXPECT_EQ(t.euler_characteristic, 1);
  EXPECT_GT(res.report.non_quads, 0);
  EXPECT_GT(res.report.boundary_vertices, 0);
  double total = 0;
  for (const auto& f : res.mesh.faces) {
    const double a = uv_area(res.mesh, f);
    EXPECT_GT(a, 0);             // counter-clockwise, not folded
    if (f.size() == 4) {
      EXPECT_LE(a, 1 + 1e-9);
    }
    total += a;
  }
  EXPECT_LE(total, scale * scale + 1e-6);
  EXPECT_GE(total, scale * scale - 2.0);
  // Interior quads are unit cells.
  int unit = 0;
  for (const auto& f : res.mesh.faces) unit += std::abs(uv_area(res.mesh, f) - 1) < 1e-9;
  EXPECT_GE(unit, static_cast<int>(std::floor((scale - 2) * (scale - 2))));
}

// The same rotated squares with the clipped polygons made quads (ExtractOptions::quadrangulate_boundary, on by
// default): all quads, the disk's topology, every vertex the boundary operations add or move on the square's
// boundary, every face counter-clockwise in the map, the cells away from the boundary untouched unit squares and
// the map's area still tiled. Over these squares each of the three boundary operations is used. One triangle is
// left (scale 5.3, θ 0.6: at a corner of the square, where a vertex on the new side would have a flat corner).
TEST(ExtractQuads, RotatedSquareBoundaryCellsBecomeQuads) {
  int collapsed = 0, split = 0, merged = 0, left = 0, clipped = 0, added = 0;
  for (const double scale : {5.3, 7.3, 9.7})
    for (const double theta : {0.1, 0.25, 0.4, 0.6})
      for (const Complex offset : {Complex(0.21, 0.13), Complex(0.5, 0.77)}) {
        SCOPED_TRACE(::testing::Message() << "scale " << scale << ", theta " << theta << ", offset " << offset);
        const auto [mesh, param] = square_map(5, scale, theta, offset);
        const ExtractionResult res = extract_quads(mesh, param);
        // (a square's corner can give a two-cornered face, dropped and counted as degenerate: not checked here)
        EXPECT_EQ(res.report.flipped_triangles + res.report.torn_seams + res.report.failed_traces, 0);
        EXPECT_EQ(res.report.dropped_faces, 0);
        EXPECT_EQ(res.report.non_quads, res.mesh.num_faces() - res.mesh.num_quads());
        left += res.report.non_quads;
        ExtractOptions off;
        off.quadrangulate_boundary = false;
        const ExtractionResult plain = extract_quads(mesh, param, off);
        clipped += plain.report.non_quads;
        // Each collapse takes one vertex away, each odd polygon made even adds one; nothing else changes them.
        EXPECT_EQ(res.mesh.num_vertices(), plain.mesh.num_vertices() + res.report.boundary_added_vertices -
                                               res.report.boundary_collapsed_triangles);
        EXPECT_LE(res.report.boundary_added_vertices, res.report.boundary_split_polygons);
        added += res.report.boundary_added_vertices;
        const testing::PolygonCheck c = testing::check_polygons(res.mesh.num_vertices(), res.mesh.faces);
        EXPECT_EQ(c.problems, 0);
        EXPECT_EQ(c.unreferenced, 0);
        EXPECT_EQ(c.euler(), 1);
        EXPECT_EQ(c.boundary_loops, 1);
        const std::vector<char> on_boundary = quad_boundary_vertices(res.mesh);
        for (int v = 0; v < res.mesh.num_vertices(); ++v) {
          const Eigen::Vector3d p = res.mesh.V.row(v);
          const double to_side = std::min({p.x(), 1 - p.x(), p.y(), 1 - p.y()});
          if (on_boundary[v]) {
            EXPECT_NEAR(to_side, 0, 1e-12) << "vertex " << v;
          }
          // φ of every vertex is the map at its position
          const Complex expected = scale * std::polar(1.0, theta) * Complex(p.x(), p.y()) + offset;
          EXPECT_NEAR(std::abs(res.mesh.uv[v] - expected), 0, 1e-9) << "vertex " << v;
        }
        double total = 0;
        for (const auto& f : res.mesh.faces) {
          const double a = uv_area(res.mesh, f);
          EXPECT_GT(a, 0);
          const bool inner = std::none_of(f.begin(), f.end(), [&](int v) { return on_boundary[v]; });
          if (inner) {
            EXPECT_NEAR(a, 1, 1e-9);
          }
          total += a;
        }
        EXPECT_LE(total, scale * scale + 1e-6);
        EXPECT_GE(total, scale * scale - 2.0);
        collapsed += res.report.boundary_collapsed_triangles;
        split += res.report.boundary_split_polygons;
        merged += res.report.boundary_merged_polygons;
      }
  EXPECT_GT(collapsed, 0);
  EXPECT_GT(split, 0);
  EXPECT_GT(merged, 0);
  EXPECT_GT(added, 0);
  EXPECT_LE(left, 1);
  EXPECT_GT(clipped, 100);
}

// Boundary on iso-lines at non-grid vertices: the square [0,6]² shifted to [0.5,6.5]×[0,6]. The bottom and top
// run along grid lines from the non-integer corners (0.5, 0) and (6.5, 6) whose iso-lines must end at the next
// grid point; the left and right sides cut the rows into half cells. 6 rows × (5 unit cells + 2 half cells).
TEST(ExtractQuads, ShiftedSquareWithBoundaryCornersOffTheGrid) {
  const auto [mesh, param] = square_map(4, 6.0, 0.0, {0.5, 0});
  const ExtractionResult res = extract_quads(mesh, param);
  expect_clean(res.report);
  EXPECT_EQ(res.mesh.num_faces(), 42);
  EXPECT_EQ(res.mesh.num_quads(), 42);
  double total = 0;
  int unit = 0;
  for (const auto& f : res.mesh.faces) {
    const double a = uv_area(res.mesh, f);
    total += a;
    unit += std::abs(a - 1) < 1e-12;
  }
  EXPECT_NEAR(total, 36.0, 1e-9);
  EXPECT_EQ(unit, 30);
  const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_TRUE(t.manifold() && t.oriented());
  EXPECT_EQ(t.euler_characteristic, 1);
}

// A displaced vertex folds the triangles around it.
testing::MeshAndMap folded_torus(int& flipped) {
  auto m = torus_map(24, 12, 17, 7);
  const int v = m.mesh.F()(100, 0);
  for (int f = 0; f < m.mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c)
      if (m.mesh.F()(f, c) == v) m.param.uv(f, c) += Complex(1.7, 0.9);
  flipped = 0;
  for (int f = 0; f < m.mesh.num_faces(); ++f) {
    const Complex e1 = m.param.uv(f, 1) - m.param.uv(f, 0), e2 = m.param.uv(f, 2) - m.param.uv(f, 0);
    flipped += (e1.real() * e2.imag() - e1.imag() * e2.real()) < 0;
  }
  return m;
}

// Without repair the folded triangles are cut out, the rest is extracted, and the output stays manifold.
TEST(ExtractQuads, CutsOutFoldsAndReportsThem) {
  int flipped_expected = 0;
  const auto [mesh, param] = folded_torus(flipped_expected);
  ASSERT_GT(flipped_expected, 0);
  ExtractOptions opt;
  opt.repair_folds = false;
  const ExtractionResult res = extract_quads(mesh, param, opt);
  EXPECT_EQ(res.report.flipped_triangles, flipped_expected);
  const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_EQ(t.non_manifold_edges + t.inconsistent_edges, 0);
  EXPECT_EQ(t.degenerate_faces, 0);
  EXPECT_GT(res.mesh.num_quads(), 17 * 7 - 20);  // only a neighbourhood of the fold is affected
  // The fold's hole is larger than the small holes that get closed, and the piece cut off inside the fold is not
  // closed into a blob: the output stays open; with or without the polygon repair, χ differs by the holes closed.
  EXPECT_FALSE(t.closed());
  opt.quadrangulate = false;
  const ExtractionResult open = extract_quads(mesh, param, opt);
  const SurfaceCounts to = surface_counts(open.mesh.num_vertices(), open.mesh.faces);
  EXPECT_EQ(open.report.filled_holes, 0);
  EXPECT_FALSE(to.closed());
  EXPECT_EQ(to.non_manifold_edges + to.inconsistent_edges + to.non_manifold_vertices + to.degenerate_faces, 0);
  EXPECT_EQ(t.euler_characteristic, to.euler_characteristic + res.report.filled_holes);  // one face per hole
}

// With repair the fold of a regular vertex is untangled and the exact quad mesh comes back.
TEST(ExtractQuads, RepairsFoldsAtRegularVertices) {
  int flipped_expected = 0;
  const auto [mesh, param] = folded_torus(flipped_expected);
  const ExtractionResult res = extract_quads(mesh, param);
  EXPECT_EQ(res.report.unfolded_triangles, flipped_expected);
  EXPECT_GE(res.report.moved_vertices, 1);
  expect_clean(res.report);
  EXPECT_EQ(res.mesh.num_quads(), 17 * 7);
  EXPECT_EQ(res.mesh.num_faces(), 17 * 7);
  const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_TRUE((t.manifold() && t.oriented()) && t.closed());
}

int count_bad(const Mesh& mesh, const Eigen::MatrixX3cd& uv) {
  int bad = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Complex e1 = uv(f, 1) - uv(f, 0), e2 = uv(f, 2) - uv(f, 0);
    bad += e1.real() * e2.imag() - e1.imag() * e2.real() <= 0;
  }
  return bad;
}

// A regular vertex next to a cone (a cube corner, valence 3) pushed through the cone (z ↦ 2.5 c − 1.5 z in its
// chart): the map stays seamless but folds. Tutte rounds are switched off: the kernel sweeps alone must untangle it, and extraction then gives the
// exact cube quad mesh back.
TEST(RepairFolds, KernelSweepsUntangleAFoldAtACone) {
  for (const auto& [n, m] : {std::pair{4, 4}, std::pair{3, 5}}) {
    auto [mesh, param] = cube_map(n, m);
    const int cone = mesh.F()(0, 0), u = mesh.F()(0, 2);  // cube corner (0, 0, 1) and P(1, 1) inside side 0
    ASSERT_EQ(mesh.fan(u).size(), 6u);
    const Complex c0 = param.uv(0, 0);
    for (const auto& fc : mesh.fan(u)) {  // all in the chart of side 0 (the seams run along the cube edges)
      ASSERT_TRUE(fc.face < 2 * n * n);
      param.uv(fc.face, fc.corner) = 2.5 * c0 - 1.5 * param.uv(fc.face, fc.corner);
    }
    const int bad = count_bad(mesh, param.uv);
    ASSERT_GT(bad, 0);
    FoldRepairOptions opt;
    opt.rounds = 0;
    const FoldRepairResult fr = repair_folds(mesh, param, opt);
    EXPECT_EQ(fr.bad_before, bad);
    EXPECT_EQ(fr.bad_after, 0);
    EXPECT_EQ(count_bad(mesh, fr.uv), 0);
    EXPECT_GE(fr.moved_vertices, 1);
    // the cone never moves
    for (const auto& fc : mesh.fan(cone)) EXPECT_EQ(fr.uv(fc.face, fc.corner), param.uv(fc.face, fc.corner));
    const ExtractionResult res = extract_quads(mesh, param);
    EXPECT_EQ(res.report.flipped_triangles + res.report.degenerate_triangles, 0);
    EXPECT_EQ(res.mesh.num_quads(), 6 * m * m);
    EXPECT_EQ(res.mesh.num_faces(), 6 * m * m);
    const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
    EXPECT_TRUE((t.manifold() && t.oriented()) && t.closed());
    EXPECT_EQ(t.euler_characteristic, 2);
  }
}

// Many random folds on a torus: the kernel sweeps never make things worse (each move keeps the incident triangles
// positive), remove most folds, and the extraction around what is left stays manifold without unused vertices.
TEST(RepairFolds, KernelSweepsNeverIncreaseFolds) {
  auto [mesh, param] = torus_map(24, 12, 17, 7);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jump(-0.8, 0.8);
  for (int v = 0; v < mesh.num_vertices(); v += 5) {
    const Complex d(jump(rng), jump(rng));
    for (const auto& fc : mesh.fan(v)) param.uv(fc.face, fc.corner) += d;  // translations only: stays seamless
  }
  const int bad = count_bad(mesh, param.uv);
  ASSERT_GT(bad, 10);
  for (int sweeps : {0, 1, 3, 40}) {
    FoldRepairOptions opt;
    opt.rounds = 0;
    opt.kernel_sweeps = sweeps;
    const FoldRepairResult fr = repair_folds(mesh, param, opt);
    EXPECT_LE(fr.bad_after, bad);
    if (sweeps == 0) {
      EXPECT_EQ(fr.bad_after, bad);
    }
    if (sweeps == 40) {
      EXPECT_EQ(fr.bad_after, 0);
    }
  }
  const ExtractionResult res = extract_quads(mesh, param);
  const testing::PolygonCheck pc = testing::check_polygons(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_EQ(pc.problems, 0);
  EXPECT_EQ(pc.unreferenced, 0);
  EXPECT_EQ(res.mesh.num_quads(), 17 * 7);
}

// A face loop running out to a vertex of valence 1 and back (x → v → x) loses the spike; nested spikes too.
TEST(QuadMesh, RemoveSpikes) {
  std::vector<int> loop = {1, 2, 3, 2, 5};
  EXPECT_EQ(remove_spikes(loop), 1);
  EXPECT_EQ(loop, (std::vector<int>{1, 2, 5}));
  loop = {1, 2, 3, 4, 3, 2, 6, 7};  // 2 → 3 → 4 → 3 → 2: two spikes
  EXPECT_EQ(remove_spikes(loop), 2);
  EXPECT_EQ(loop, (std::vector<int>{1, 2, 6, 7}));
  loop = {4, 9, 4, 5, 6};  // across the start of the loop
  EXPECT_EQ(remove_spikes(loop), 1);
  EXPECT_EQ(loop, (std::vector<int>{4, 5, 6}));
  loop = {1, 2, 3, 4};
  EXPECT_EQ(remove_spikes(loop), 0);
  EXPECT_EQ(loop.size(), 4u);
}

// Unused vertices are removed, the others renumbered in order of first use with their data.
TEST(QuadMesh, RemoveUnusedVerticesKeepsDataAndOrder) {
  QuadMesh q;
  q.V.resize(6, 3);
  q.uv.resize(6);
  q.source_face.resize(6);
  q.on_grid.resize(6);
  for (int v = 0; v < 6; ++v) {
    q.V.row(v) << v, 10 * v, 100 * v;
    q.uv[v] = Complex(v, -v);
    q.source_face[v] = 7 * v;
    q.on_grid[v] = v % 2;
  }
  q.faces = {{5, 2, 3, 0}};  // 1 and 4 unused
  EXPECT_EQ(remove_unused_vertices(q), 2);
  ASSERT_EQ(q.num_vertices(), 4);
  EXPECT_EQ(q.faces[0], (std::vector<int>{0, 1, 2, 3}));
  const int old_of[4] = {5, 2, 3, 0};
  for (int v = 0; v < 4; ++v) {
    EXPECT_EQ(q.V(v, 1), 10 * old_of[v]);
    EXPECT_EQ(q.uv[v], Complex(old_of[v], -old_of[v]));
    EXPECT_EQ(q.source_face[v], 7 * old_of[v]);
    EXPECT_EQ(q.on_grid[v], old_of[v] % 2);
  }
  EXPECT_EQ(surface_counts(q.num_vertices(), q.faces).isolated_vertices, 0);
}

// A broken seam (translation off the lattice) is cut open and reported instead of producing garbage.
TEST(ExtractQuads, NonSeamlessTransitionIsCutAndReported) {
  auto [mesh, param] = torus_map(24, 12, 17, 7);
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (f % 2 == 0 && (f / 2) / 12 == 0)
      for (int c = 0; c < 3; ++c) param.uv(f, c) += Complex(0.3, 0);
  const ExtractionResult res = extract_quads(mesh, param);
  EXPECT_GT(res.report.torn_seams, 0);
  const SurfaceCounts t = surface_counts(res.mesh.num_vertices(), res.mesh.faces);
  EXPECT_EQ(t.non_manifold_edges + t.inconsistent_edges, 0);
  EXPECT_EQ(t.degenerate_faces, 0);
}

TEST(ExtractQuads, RejectsMismatchedSizes) {
  auto [mesh, param] = torus_map(8, 4, 3, 2);
  param.uv.conservativeResize(3, 3);
  EXPECT_THROW(extract_quads(mesh, param), InputError);
}

}  // namespace
}  // namespace quadcover
