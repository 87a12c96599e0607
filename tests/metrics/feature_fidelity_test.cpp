// Feature fidelity (issue 15): known answers on generated meshes, thread independence, and a real remesh.
#include "metrics/feature_fidelity.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <set>

#include "common/errors.h"
#include "field/compute_frame_field.h"
#include "param/parameterize.h"
#include "quad/extract_quads.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// Folds a point of the unit square up by 90° along x = 0.5 (identity for fold = false).
Eigen::Vector3d fold(double x, double y, bool folded) {
  if (!folded || x <= 0.5) return {x, y, 0};
  return {0.5, y, x - 0.5};
}

// The unit square (optionally folded) as an n × n quad grid.
std::pair<Eigen::MatrixX3d, std::vector<std::vector<int>>> quad_grid(int n, bool folded) {
  Eigen::MatrixX3d V((n + 1) * (n + 1), 3);
  std::vector<std::vector<int>> F;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) V.row(j * (n + 1) + i) = fold(double(i) / n, double(j) / n, folded).transpose();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int v = j * (n + 1) + i;
      F.push_back({v, v + 1, v + n + 2, v + n + 1});
    }
  return {V, F};
}

// make_grid(n) (triangles of the unit square), optionally folded.
Mesh reference(int n, bool folded) {
  const Mesh grid = testing::make_grid(n);
  Eigen::MatrixX3d V = grid.V();
  for (int v = 0; v < V.rows(); ++v) V.row(v) = fold(V(v, 0), V(v, 1), folded).transpose();
  return Mesh::from_triangles(V, grid.F());
}

void expect_exact(const FeatureFidelityPart& p) {
  EXPECT_GT(p.samples, 0);
  EXPECT_DOUBLE_EQ(p.covered_percent, 100.0);
  EXPECT_NEAR(p.max, 0, 1e-12);
  EXPECT_NEAR(p.mean, 0, 1e-12);
}

TEST(FeatureFidelity, GridContainingTheBoundaryCoversIt) {
  const Mesh ref = reference(16, false);
  const auto [V, F] = quad_grid(4, false);
  const FeatureFidelity f = feature_fidelity(ref, V, F);
  EXPECT_DOUBLE_EQ(f.h, 0.25);
  EXPECT_EQ(f.boundary.edges, 64);
  // spacing h/20 on edges of length 1/16: ceil(0.0625 / 0.0125) = 5 samples per edge.
  EXPECT_EQ(f.boundary.samples, 64 * 5);
  EXPECT_EQ(f.sharp.samples, 0);
  expect_exact(f.boundary);
  expect_exact(f.total);
}

TEST(FeatureFidelity, FoldedGridCoversCreaseAndBoundary) {
  const Mesh ref = reference(16, true);
  const auto [V, F] = quad_grid(4, true);
  const FeatureFidelity f = feature_fidelity(ref, V, F);
  EXPECT_EQ(f.sharp.edges, 16);  // the crease x = 0.5, a curve of 16 edges at 90°
  EXPECT_EQ(f.followed.edges, 16);  // long enough for the field to follow it
  expect_exact(f.sharp);
  expect_exact(f.followed);
  expect_exact(f.boundary);
  EXPECT_EQ(f.total.samples, f.sharp.samples + f.boundary.samples);
}

TEST(FeatureFidelity, ShortCreasesCountThoughTheFieldDoesNotFollowThem) {
  // A crease of 4 edges at 90°: too short for a feature curve of the field (8 edges), still a sharp edge of the
  // metric's definition (dihedral > 35°). An output flat at the fold line's height misses it.
  const Mesh ref = reference(4, true);
  const FeatureFidelity f = feature_fidelity(ref, quad_grid(4, true).first, quad_grid(4, true).second);
  EXPECT_EQ(f.sharp.edges, 4);
  EXPECT_EQ(f.followed.edges, 0);
  EXPECT_EQ(f.followed.samples, 0);
  expect_exact(f.sharp);
  EXPECT_EQ(f.total.samples, f.sharp.samples + f.boundary.samples);
  EXPECT_TRUE(feature_fidelity_to_json(f)["followed"]["covered_percent"].is_null());
  auto [V, F] = quad_grid(3, false);  // flat, lines at x = 1/3 and 2/3: the crease x = 0.5 lies between them
  const FeatureFidelity missed = feature_fidelity(ref, V, F);
  EXPECT_EQ(missed.sharp.edges, 4);
  EXPECT_LT(missed.sharp.covered_percent, 100.0);
  // With the field's own detection as the definition, the same crease would not be measured at all.
  FeatureFidelityOptions field_curves;
  field_curves.features = FeatureOptions{};
  EXPECT_EQ(feature_fidelity(ref, V, F, field_curves).sharp.edges, 0);
}

TEST(FeatureFidelity, ShiftedCopyIsAtTheShift) {
  const Mesh ref = reference(16, false);
  auto [V, F] = quad_grid(4, false);
  V.col(2).array() += 0.03;  // every boundary sample lies 0.03 = 0.12 h below an output boundary edge
  const FeatureFidelity f = feature_fidelity(ref, V, F);
  EXPECT_NEAR(f.total.mean, 0.12, 1e-12);
  EXPECT_NEAR(f.total.p95, 0.12, 1e-12);
  EXPECT_NEAR(f.total.max, 0.12, 1e-12);
  EXPECT_DOUBLE_EQ(f.total.covered_percent, 0.0);
  FeatureFidelityOptions loose;
  loose.covered_within = 0.125;
  EXPECT_DOUBLE_EQ(feature_fidelity(ref, V, F, loose).total.covered_percent, 100.0);
}

TEST(FeatureFidelity, CreaseMissedByHalfACellIsAtTheKnownDistance) {
  // Output grid with lines at x = 0, 0.2, ..., 1 folded at 0.5: the crease's nearest output edges are the lines
  // x = 0.4 (flat) and x = 0.6 (up), both 0.1 away, and the chords from (0.4, y_k, 0) to (0.5, y_k, 0.1) at the
  // grid rows y_k, 0.1/√2 away from the crease point (0.5, y_k, 0).
  const Mesh ref = reference(20, true);
  Eigen::MatrixX3d V(36, 3);
  std::vector<std::vector<int>> F;
  const double xs[6] = {0, 0.2, 0.4, 0.6, 0.8, 1.0};
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) V.row(j * 6 + i) = fold(xs[i], 0.2 * j, true).transpose();
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) F.push_back({j * 6 + i, j * 6 + i + 1, j * 6 + i + 7, j * 6 + i + 6});
  const FeatureFidelity f = feature_fidelity(ref, V, F);
  std::set<std::pair<int, int>> edges;
  for (const auto& q : F)
    for (int k = 0; k < 4; ++k) edges.emplace(std::minmax(q[k], q[(k + 1) % 4]));
  double sum = 0;
  for (const auto& [a, b] : edges) sum += (V.row(a) - V.row(b)).norm();
  ASSERT_EQ(edges.size(), 60u);
  EXPECT_NEAR(f.h, sum / 60, 1e-12);
  // Crease sample (0.5, y): nearest is the chord at the closest row, distance sqrt(0.1²/2 + dy²), capped by 0.1.
  EXPECT_NEAR(f.sharp.max, 0.1 / f.h, 1e-9);
  EXPECT_GT(f.sharp.mean, 0.1 / std::sqrt(2.0) / f.h);
  EXPECT_LT(f.sharp.mean, 0.1 / f.h);
  EXPECT_DOUBLE_EQ(f.sharp.covered_percent, 0.0);
}

TEST(FeatureFidelity, RejectsAnOutputWithoutEdges) {
  const Mesh ref = reference(4, false);
  EXPECT_THROW(feature_fidelity(ref, Eigen::MatrixX3d::Zero(3, 3), {{0, 1, 2}}), InputError);
  EXPECT_THROW(feature_fidelity(ref, Eigen::MatrixX3d::Zero(3, 3), {{0, 1, 5}}), InputError);
}

TEST(FeatureFidelity, FandiskRemeshIsSaneAndThreadIndependent) {
  const Mesh mesh = testing::load_test_mesh("fandisk");
  const Parameterization P = parameterize(mesh, compute_frame_field(mesh));
  const ExtractionResult ex = extract_quads(mesh, P);
  ASSERT_GT(ex.mesh.num_faces(), 100);
  const FeatureFidelity f = feature_fidelity(mesh, ex.mesh.V, ex.mesh.faces);
  EXPECT_EQ(f.boundary.samples, 0);  // closed
  EXPECT_GT(f.sharp.edges, 300);
  EXPECT_EQ(f.total.samples, f.sharp.samples);
  EXPECT_GT(f.total.covered_percent, 20.0);  // grid vertices are on the surface; many sharp edges are kept
  EXPECT_LE(f.total.mean, f.total.p95);
  EXPECT_LE(f.total.p95, f.total.max);
  EXPECT_LT(f.total.p95, 1.0);  // never further than an edge length: the output lies on the surface
  const nlohmann::json j = feature_fidelity_to_json(f);
  EXPECT_TRUE(j["boundary"]["p95"].is_null());
  EXPECT_DOUBLE_EQ(j["total"]["p95"].get<double>(), f.total.p95);
  FeatureFidelity serial;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    serial = feature_fidelity(mesh, ex.mesh.V, ex.mesh.faces);
  }
  EXPECT_EQ(serial.total.mean, f.total.mean);
  EXPECT_EQ(serial.total.max, f.total.max);
  EXPECT_EQ(serial.total.covered_percent, f.total.covered_percent);
}

}  // namespace
}  // namespace quadcover
