// Meshes made in the test that are hard for a seamless map (issue 14): coarse triangulations with cones close
// together, an inward-facing (inverted) surface, slivers, a coarse box with sharp creases. Each default remesh must
// give a valid map (no flipped or collapsed triangle, no vertex wound other than the field says) and keep the
// input's topology, all quads where the input is closed; so must the ones with curves with --round-curves.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "metrics/feature_fidelity.h"
#include "metrics/quad_quality.h"
#include "param/density.h"
#include "param/seams.h"
#include "pipeline/memory_budget.h"
#include "pipeline/remesh_mesh.h"
#include "pipeline/validity_retries.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

/// A unit cube whose six squares are fans of four triangles around their centres: 14 vertices, 24 triangles, twelve
/// 90° creases (sharp features) and eight corners of valence 3-6.
Mesh coarse_cube() {
  Eigen::MatrixX3d V(14, 3);
  for (int k = 0; k < 8; ++k) V.row(k) << ((k >> 2) & 1), ((k >> 1) & 1), (k & 1);
  const int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  Eigen::MatrixX3i F(24, 3);
  for (int q = 0; q < 6; ++q) {
    V.row(8 + q).setZero();
    for (int k = 0; k < 4; ++k) V.row(8 + q) += 0.25 * V.row(quads[q][k]);
    for (int k = 0; k < 4; ++k) F.row(4 * q + k) << quads[q][k], quads[q][(k + 1) % 4], 8 + q;
  }
  return Mesh::from_triangles(V, F);
}

/// The remesh job of `mesh` with `options`, checked: a valid map, the input's topology, all quads where the input is
/// closed, and an extraction that cut nothing out.
RemeshJob expect_valid_job(const Mesh& mesh, const PipelineOptions& options) {
  RemeshJob job = remesh_mesh(mesh, options);
  const Mesh& map_mesh = job.param.mesh(mesh);
  EXPECT_EQ(flipped_triangles(map_mesh, job.param.map.uv).non_positive, 0);
  EXPECT_TRUE(wrong_winding_vertices(map_mesh, job.param.map).empty());
  EXPECT_TRUE(job.surface.same_topology);
  if (mesh.num_boundary_loops() == 0) {
    EXPECT_EQ(job.surface.output.non_quads, 0);
  }
  // From an injective map the extraction cuts nothing out (issue 14 item 5).
  const ExtractionReport& cut = job.extraction.report;
  EXPECT_EQ(cut.flipped_triangles + cut.degenerate_triangles + cut.collapsed_edges + cut.filled_holes, 0);
  for (const std::string& w : job.param.warnings) EXPECT_EQ(w.find("not valid"), std::string::npos) << w;
  return job;
}

/// Returns whether the kept map rounded the curves with the periods or fell back from doing so.
bool expect_valid_remesh(const Mesh& mesh, int quads, const std::string& what, bool round_curves = false) {
  SCOPED_TRACE(what + (round_curves ? ", curves rounded with the periods" : ""));
  PipelineOptions options;
  options.param.density.target_quads = quads;
  options.param.alignment.round_with_periods = round_curves;
  const RemeshJob job = expect_valid_job(mesh, options);
  EXPECT_GT(job.surface.output.faces, quads / 2);
  EXPECT_LT(job.surface.output.faces, 2 * quads);
  const auto& rounding = job.param.map.diagnostics.rounding;
  return rounding.curve_lines > 0 || rounding.curve_rounding_dropped;
}

// Components of very different sizes: one h for all would leave the small copies a few quads for their branch
// points, and their maps folded or wound wrong (BENCHMARKS.md, "Components of very different sizes"). Each gets its
// own density (param/density.h fix_component_density), the large one keeps h.
TEST(HardCases, ComponentsOfVeryDifferentSizes) {
  const Mesh mesh = testing::scaled_copies(testing::load_test_mesh("bunny_3k"), {1.0, 0.05, 0.3});
  for (const int quads : {0, 6500}) {
    SCOPED_TRACE(quads);
    PipelineOptions options;
    options.param.density.target_quads = quads;
    const RemeshJob job = expect_valid_job(mesh, options);
    const std::vector<double>& rho = job.param.map.component_density;
    ASSERT_EQ(rho.size(), 3u);
    EXPECT_EQ(rho[0], 1.0);
    EXPECT_GT(rho[2], 1.0);
    EXPECT_GT(rho[1], rho[2]);  // the smallest copy the finest
    if (quads > 0) {
      EXPECT_NEAR(job.surface.output.faces, quads, 0.03 * quads);
    }
  }
}

TEST(HardCases, CoarseSpheresWithManyQuadsPerTriangle) {
  expect_valid_remesh(testing::make_ellipsoid(1), 100, "octahedron subdivided once, 100 quads");
  expect_valid_remesh(testing::make_ellipsoid(2), 300, "subdivided twice, 300 quads");
  expect_valid_remesh(testing::make_ellipsoid(2, 1.0, 0.6, 0.35), 300, "a flat ellipsoid");
}

/// The sphere of make_ellipsoid(level) turned by 0.5 rad about (1, 2, 3), then scaled to 10 × 1 × 0.1: no edge loop
/// runs along the rim, whose triangles form a band between two crease chains a few hundredths of a quad apart.
Mesh tilted_flat_ellipsoid(int level) {
  const Mesh sphere = testing::make_ellipsoid(level);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::MatrixX3d V = sphere.V() * turn.transpose();
  V.col(0) *= 10.0;
  V.col(2) *= 0.1;
  return Mesh::from_triangles(V, sphere.F());
}

// The rim band is pinned to one iso-line and the map squeezes its triangles into slivers micro-units high.
TEST(HardCases, AVeryFlatEllipsoid) {
  for (const int level : {3, 4})
    for (const int quads : {150, 2000})
      expect_valid_remesh(tilted_flat_ellipsoid(level), quads,
                          "flat ellipsoid, level " + std::to_string(level) + ", " + std::to_string(quads) + " quads");
}

TEST(HardCases, AnInwardFacingSurfaceIsAsValidAsTheOutwardOne) {
  expect_valid_remesh(testing::with_faces_reversed(testing::make_ellipsoid(2)), 300, "inverted sphere");
  expect_valid_remesh(testing::with_faces_reversed(testing::make_torus(16, 8)), 200, "inverted torus");
}

TEST(HardCases, CoarseTorusAndSlivers) {
  expect_valid_remesh(testing::make_torus(10, 5, 1.0, 0.4), 200, "10 x 5 torus");
  // 48 × 2 quads of aspect ratio 15 on an open cylinder: every triangle a sliver.
  expect_valid_remesh(testing::make_cylinder(48, 2, 1.0, 4.0), 100, "sliver cylinder");
}

TEST(HardCases, ACoarseCubeWithSharpCreases) {
  expect_valid_remesh(coarse_cube(), 60, "cube, 60 quads");
  expect_valid_remesh(coarse_cube(), 200, "cube, 200 quads");
}

// Boundaries (issue 17 item 6 pins v = 0 on them in the optimizer too): a coarse disk of 12 triangles, a plate with
// 16 small square holes, and a torus beside an open cylinder in one mesh.
TEST(HardCases, CoarseSurfacesWithBoundary) {
  expect_valid_remesh(testing::make_fan(12, false), 100, "disk of 12 triangles");
  const Mesh grid = testing::make_grid(10);
  expect_valid_remesh(Mesh::from_triangles(grid.V(), testing::grid_faces_with_holes(grid, 10)), 400,
                      "plate with 16 holes");
  expect_valid_remesh(testing::make_torus_and_cylinder(), 300, "torus and open cylinder");
}

// Holes shorter than 4 default quad edges: the default density is made finer for them (param/density.h), so the
// quads keep every hole; at the coarser density the quads close over them, and the job says so.
TEST(HardCases, SmallHolesKeptAtTheDefaultDensity) {
  const Mesh grid = testing::make_grid(10);
  const Mesh plate = Mesh::from_triangles(grid.V(), testing::grid_faces_with_holes(grid, 10));
  const RemeshJob job = remesh_mesh(plate, PipelineOptions{});
  EXPECT_TRUE(job.surface.same_topology);
  EXPECT_EQ(job.surface.output.boundary_loops, 17);
  EXPECT_GT(job.param.density.raised.loop, 1);  // a hole, not the outer loop (number 1)
  EXPECT_GT(job.param.density.raised.quads_factor, 4.0);
  for (const BoundaryLoopCheck& loop : job.boundary_loops) EXPECT_FALSE(loop.closed_over) << loop.loop;
  const auto said = [&](const RemeshJob& j, const std::string& what) {
    return std::any_of(j.param.warnings.begin(), j.param.warnings.end(),
                       [&](const std::string& w) { return w.find(what) != std::string::npos; });
  };
  EXPECT_TRUE(said(job, "boundary loop " + std::to_string(job.param.density.raised.loop) + " (through vertex"));
  PipelineOptions coarser;  // the default h without the rule
  coarser.param.density.edge_length = job.param.map.edge_length * std::sqrt(job.param.density.raised.quads_factor);
  const RemeshJob closed = remesh_mesh(plate, coarser);
  EXPECT_FALSE(closed.surface.same_topology);
  EXPECT_EQ(closed.param.density.raised.loop, 0);
  EXPECT_TRUE(said(closed, "closed over by the quads"));
  // Memory for the coarser density but not for the finer one: the job keeps the coarser and says why.
  PipelineOptions tight;
  const double finer_quads = plate.total_area() / std::pow(job.param.map.edge_length, 2);
  tight.max_memory_bytes =
      static_cast<std::int64_t>(kBytesPerInputFace * plate.num_faces() + kBytesPerQuad * finer_quads / 2);
  const RemeshJob held = remesh_mesh(plate, tight);
  EXPECT_EQ(held.param.density.raised.loop, 0);
  EXPECT_NEAR(held.param.map.edge_length, coarser.param.density.edge_length, 1e-9 * coarser.param.density.edge_length);
  EXPECT_TRUE(said(held, "the default density was not made finer for boundary loop " +
                             std::to_string(job.param.density.raised.loop)));
  EXPECT_FALSE(held.surface.same_topology);
}

/// A ring (R = 1) whose tube (radius 0.3) pinches to radius 0.03 over a quarter of its length, like a thin handle
/// on a thick body: 200 × 24 quads split into triangles. The default h, twice the mean edge length, is longer than
/// a third of the thin part's circumference.
Mesh pinched_torus() {
  const int n_major = 200, n_minor = 24;
  Eigen::MatrixX3d V(n_major * n_minor, 3);
  Eigen::MatrixX3i F(2 * n_major * n_minor, 3);
  const auto id = [&](int i, int j) { return (i % n_major) * n_minor + j % n_minor; };
  for (int i = 0; i < n_major; ++i) {
    const double u = 2 * std::numbers::pi * i / n_major, from_pinch = std::min(u, 2 * std::numbers::pi - u);
    const double t = std::clamp((from_pinch - 0.4) / 0.4, 0.0, 1.0), r = 0.03 + 0.27 * t * t * (3 - 2 * t);
    for (int j = 0; j < n_minor; ++j) {
      const double v = 2 * std::numbers::pi * j / n_minor;
      V.row(id(i, j)) << (1 + r * std::cos(v)) * std::cos(u), (1 + r * std::cos(v)) * std::sin(u), r * std::sin(v);
      F.row(2 * id(i, j)) << id(i, j), id(i + 1, j), id(i + 1, j + 1);
      F.row(2 * id(i, j) + 1) << id(i, j), id(i + 1, j + 1), id(i, j + 1);
    }
  }
  return Mesh::from_triangles(V, F);
}

// A part thinner than the default quad edge that folds nothing: at the default density its quads fall apart (the
// topology changes), so the job is made again at half the quad edge (pipeline/retry_until_valid.h under_resolved)
// and says so; a density the user gives is kept, with the change of topology reported.
TEST(HardCases, AThinHandleMakesTheDefaultDensityFiner) {
  const Mesh mesh = pinched_torus();
  const RemeshJob job = expect_valid_job(mesh, PipelineOptions{});
  EXPECT_EQ(job.surface.output.components, 1);
  EXPECT_TRUE(std::any_of(job.param.warnings.begin(), job.param.warnings.end(), [](const std::string& w) {
    return w.find(
               "the default density was too coarse for this shape (a part thinner than the quad edge): made 4 times") !=
           std::string::npos;
  }));
  PipelineOptions given;  // the density of the first attempt, not made finer
  given.param.density.edge_length = 2 * job.param.map.edge_length;
  given.validity_retries = 0;
  EXPECT_FALSE(remesh_mesh(mesh, given).surface.same_topology);
}

// A flat disk fanned around its one interior vertex (a planar CAD face): the field aligned to the round boundary
// has index +1 there, with no other interior vertex to split it over, and the map folded flat ("the map holds about
// 0 quads", exit 2). The edges at the centre are split (pipeline/cone_refinement.h) and the field made again.
TEST(HardCases, AFanDiskGetsVerticesForItsCones) {
  for (const int n : {12, 100}) {
    SCOPED_TRACE(n);
    const Mesh disk = testing::make_fan(n, false, 0.0);
    const RemeshJob job = expect_valid_job(disk, PipelineOptions{});
    EXPECT_EQ(job.param.cone_splits, n);
    EXPECT_EQ(job.param.refinement.added_faces, 2 * n);
    EXPECT_EQ(job.surface.output.non_quads, 0);
    EXPECT_TRUE(std::any_of(job.param.warnings.begin(), job.param.warnings.end(), [&](const std::string& w) {
      return w.find(std::to_string(n) + " at field singularities of index 3/4 or more") != std::string::npos;
    }));
  }
  // The corners of a tetrahedron are half cones with no interior vertex beside them either: those are mapped as
  // they are (quad vertices of valence 2), the triangulation is not refined.
  Eigen::MatrixX3d V(4, 3);
  V << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  Eigen::MatrixX3i F(4, 3);
  F << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
  const RemeshJob tetrahedron = expect_valid_job(Mesh::from_triangles(V, F), PipelineOptions{});
  EXPECT_EQ(tetrahedron.param.cone_splits, 0);
  EXPECT_FALSE(tetrahedron.param.refinement.mesh);
}

// A small hole drilled through a coarse CAD plate (two rims of 16 edges, each about 6 quad edges around at the
// default density): aligned to the rims on the plate's side too, the field is polar around the hole and the quads
// shrink towards it like log r; with the plate's side of each rim left free (PipelineOptions::square_hole_grid_units,
// field/crease_loops.h) the field stays parallel, the hole comes out square and the grid even. The plate's outline
// (chains of 4 edges) is left unfollowed here (crisp_crease_degrees = 0): followed, its corners hold the field
// parallel whatever the rims do, as the many holes of bench/hard_cases.py's bolted_plate do not.
TEST(HardCases, ASmallHoleThroughAPlateComesOutSquareInAnEvenGrid) {
  const Mesh plate = testing::make_drilled_plate(16, 0.15);
  PipelineOptions square_options;
  square_options.param.features.crisp_crease_degrees = 0;
  const RemeshJob square = expect_valid_job(plate, square_options);
  const double h = square.param.map.edge_length;
  ASSERT_EQ(square.param.options.param.density.hole_rims.size(), 2u);
  EXPECT_LT(square.param.options.param.density.hole_rims[0].length, 8 * h);
  PipelineOptions round_options = square_options;
  round_options.square_hole_grid_units = 0;
  round_options.param.density.edge_length = h;  // the same density
  const RemeshJob round = expect_valid_job(plate, round_options);
  EXPECT_TRUE(round.param.options.param.density.hole_rims.empty());
  const double rsd_square = quad_quality(square.extraction.mesh).rsd_edge_length;
  const double rsd_round = quad_quality(round.extraction.mesh).rsd_edge_length;
  EXPECT_LT(rsd_square, 0.6 * rsd_round) << rsd_square << " vs " << rsd_round;
  EXPECT_EQ(square.surface.output.genus, 1);
  // Rims longer than square_hole_grid_units quad edges stay followed on both sides.
  PipelineOptions fine;
  fine.param.density.edge_length = square.param.options.param.density.hole_rims[0].length / 10;
  EXPECT_TRUE(remesh_mesh(plate, fine).param.options.param.density.hole_rims.empty());
}

// A gear as a coarse CAD export (testing::make_gear): its outlines and tooth corners are chains of at most 3 sharp
// edges, too short to be feature curves, but crisp creases between corners (FeatureOptions::crisp_crease_degrees).
// Followed, the quad edges run along the teeth: most of the sharp edges are covered (feature fidelity, within 0.1 h)
// against a fifth with chains only (72.7 % and 17.1 %, 2026-12-08); the map is valid either way.
TEST(HardCases, AGearKeepsItsTeeth) {
  const Mesh gear = testing::make_gear(12);
  const auto covered = [&](const RemeshJob& job) {
    return feature_fidelity(gear, job.extraction.mesh.V, job.extraction.mesh.faces).sharp.covered_percent;
  };
  const RemeshJob crisp = expect_valid_job(gear, PipelineOptions{});
  PipelineOptions chains_only;
  chains_only.param.features.crisp_crease_degrees = 0;
  const RemeshJob chains = expect_valid_job(gear, chains_only);
  EXPECT_GT(covered(crisp), 60);
  EXPECT_LT(covered(chains), 30);
  EXPECT_EQ(crisp.param.crisp_creases, 2 * 96 + 2 * 24);
  EXPECT_EQ(chains.param.crisp_creases, 0);
  // At a requested density, creases shorter than its quad edge are not followed (FeatureOptions::crisp_min_length):
  // at 300 quads (h 0.16) the 0.157-long roots go, at 150 (h 0.22) everything.
  for (const int quads : {300, 150}) {
    PipelineOptions coarse;
    coarse.param.density.target_quads = quads;
    coarse.validity_retries = 0;
    const ParamJob job = parameterize_mesh(gear, coarse);
    EXPECT_DOUBLE_EQ(job.options.param.features.crisp_min_length, target_edge_length(gear, coarse.param.density));
    EXPECT_EQ(job.crisp_creases, quads == 300 ? 240 - 72 : 0) << quads;
  }
}

// The same meshes with curves (creases, boundaries) with --round-curves (param/curve_rounding.h): every line pinned
// or, where that map is less valid, the period-matrix map; valid either way, with the input's topology.
TEST(HardCases, CurvesRoundedWithThePeriodsStayValid) {
  int engaged = 0;
  engaged += expect_valid_remesh(coarse_cube(), 60, "cube, 60 quads", true);
  engaged += expect_valid_remesh(coarse_cube(), 200, "cube, 200 quads", true);
  engaged += expect_valid_remesh(testing::make_cylinder(48, 2, 1.0, 4.0), 100, "sliver cylinder", true);
  engaged += expect_valid_remesh(testing::make_fan(12, false), 100, "disk of 12 triangles", true);
  const Mesh grid = testing::make_grid(10);
  engaged += expect_valid_remesh(Mesh::from_triangles(grid.V(), testing::grid_faces_with_holes(grid, 10)), 400,
                                 "plate with 16 holes", true);
  engaged += expect_valid_remesh(testing::make_torus_and_cylinder(), 300, "torus and open cylinder", true);
  EXPECT_GT(engaged, 0);  // 3 of the 6 have lines of 3 grid units (2026-12-03)
}

}  // namespace
}  // namespace quadcover
