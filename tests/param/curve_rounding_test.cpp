// The periods and the curves' integers rounded together (param/curve_rounding.h).
#include "param/curve_rounding.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.h"
#include "field/compute_frame_field.h"
#include "param/parameterize.h"
#include "param/seams.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

ParamOptions rounding_the_curves(bool with_periods) {
  ParamOptions o;
  o.alignment.round_with_periods = with_periods;
  return o;
}

/// The mesh's map with the period-matrix rounding alone (D, the default) and with the curves rounded with the periods
/// (R).
struct BothMaps {
  Mesh mesh;
  Parameterization D, R;
};

BothMaps both_maps(const char* name) {
  BothMaps m{testing::load_test_mesh(name), {}, {}};
  const FrameField field = compute_frame_field(m.mesh);
  m.D = parameterize(m.mesh, field, rounding_the_curves(false));
  m.R = parameterize(m.mesh, field, rounding_the_curves(true));
  return m;
}

int enforced_lines(const Parameterization& P) {
  int n = 0;
  for (const auto& c : P.aligned_curves) n += c.enforced;
  return n;
}

// lilium_disk's boundary is one line of the field's frame that, with the period-matrix rounding, closes on itself
// one integer off and is left free. Rounded with the periods, the loop's closing condition holds and the whole
// boundary is one integer iso-line; the energy the rounding predicted from its responses is the harmonic energy of
// the constrained correction solved afresh.
TEST(CurveRounding, PutsTheBoundaryLoopOnOneIsoLineAtThePredictedEnergy) {
  const auto [mesh, D, R] = both_maps("lilium_disk");
  ASSERT_EQ(D.aligned_curves.size(), 1u);
  ASSERT_EQ(R.aligned_curves.size(), 1u);
  EXPECT_FALSE(D.aligned_curves[0].enforced);
  EXPECT_EQ(D.aligned_curves[0].left_free_because, "closes on itself with another integer");
  EXPECT_EQ(D.diagnostics.rounding.curve_lines, 0);
  const auto& r = R.diagnostics.rounding;
  EXPECT_EQ(r.curve_lines, 1);
  EXPECT_GT(r.curve_conditions, 0);
  EXPECT_EQ(r.curve_conditions_met, r.curve_conditions);
  EXPECT_TRUE(R.aligned_curves[0].enforced) << R.aligned_curves[0].left_free_because;
  EXPECT_LT(R.aligned_curves[0].max_deviation, 1e-9 * (1 + std::abs(R.aligned_curves[0].value)));
  EXPECT_EQ(R.aligned_curves[0].value, std::round(R.aligned_curves[0].value));
  EXPECT_NEAR(r.energy_rounded, R.energy_harmonic, 1e-6 * R.energy_harmonic);
  EXPECT_TRUE(measure_seams(mesh, R.uv, 1e-9).seamless);
  EXPECT_EQ(R.diagnostics.alignment_conflicts, 0);
}

// On a scan with noisy creases the limits of the free map leave most crease lines free; rounded with the periods,
// every line of at least the minimum length is pinned exactly, and the seams stay exact.
TEST(CurveRounding, PinsTheLinesTheLimitsLeftFreeExactly) {
  const auto [mesh, D, R] = both_maps("fertility_genus4");
  EXPECT_GT(R.diagnostics.rounding.curve_lines, 0);
  EXPECT_GT(enforced_lines(R), enforced_lines(D));
  for (const auto& c : R.aligned_curves) {
    if (!c.enforced) {
      EXPECT_FALSE(c.left_free_because.empty());
      continue;
    }
    EXPECT_LT(c.max_deviation, 1e-9 * (1 + std::abs(c.value)));
  }
  EXPECT_TRUE(measure_seams(mesh, R.uv, 1e-9).seamless);
}

// Off (the default) or with nothing to pin, the map is the period-matrix rounding's, bit for bit.
TEST(CurveRounding, WithoutCurvesTheMapIsUnchanged) {
  const auto [mesh, D, R] = both_maps("torus_5k");
  EXPECT_EQ(R.diagnostics.rounding.curve_lines, 0);
  EXPECT_TRUE(D.uv == R.uv);
}

// On a component meshed ρ times finer (DensityOptions::component_density) a line's length counts in that component's
// grid units: mech_holes_shark at density factor 2 pins the lines it pins at half the edge length, more than at the
// edge length itself.
TEST(CurveRounding, CountsTheLinesLengthsInTheirComponentsGridUnits) {
  const Mesh mesh = testing::load_test_mesh("mech_holes_shark");
  const FrameField field = compute_frame_field(mesh);
  const Parameterization coarse = parameterize(mesh, field, rounding_the_curves(true));
  ParamOptions half = rounding_the_curves(true), finer = half;
  half.density.edge_length = coarse.edge_length / 2;
  finer.density.edge_length = coarse.edge_length;
  finer.density.component_density = {2.0};
  const int at_half = parameterize(mesh, field, half).diagnostics.rounding.curve_lines;
  EXPECT_GT(at_half, coarse.diagnostics.rounding.curve_lines);
  EXPECT_EQ(parameterize(mesh, field, finer).diagnostics.rounding.curve_lines, at_half);
}

// CurveAlignmentOptions::free_line_vertices: the lines through the given vertices are not rounded with the periods
// and stay free with that reason; the lines away from them are still pinned exactly.
TEST(CurveRounding, FreesExactlyTheLinesThroughTheGivenVertices) {
  const Mesh mesh = testing::load_test_mesh("fandisk");
  const FrameField field = compute_frame_field(mesh);
  const Parameterization all = parameterize(mesh, field, rounding_the_curves(true));
  ASSERT_GT(enforced_lines(all), 2);
  int line = -1;  // the first enforced line; free the lines through the first vertex of its first edge
  for (std::size_t k = 0; k < all.aligned_curves.size() && line < 0; ++k)
    if (all.aligned_curves[k].enforced) line = static_cast<int>(k);
  ParamOptions options = rounding_the_curves(true);
  const int vertex = mesh.E()(all.aligned_curves[line].edges.front(), 0);
  options.alignment.free_line_vertices = {vertex};
  const Parameterization freed = parameterize(mesh, field, options);
  ASSERT_EQ(freed.aligned_curves.size(), all.aligned_curves.size());
  int freed_lines = 0;
  for (std::size_t k = 0; k < freed.aligned_curves.size(); ++k) {
    const auto& c = freed.aligned_curves[k];
    bool through = false;
    for (const int e : c.edges) through = through || mesh.E()(e, 0) == vertex || mesh.E()(e, 1) == vertex;
    SCOPED_TRACE(k);
    if (through && all.aligned_curves[k].enforced) {
      EXPECT_FALSE(c.enforced);
      EXPECT_EQ(c.left_free_because, "freed: the map with it pinned was not valid there");
      ++freed_lines;
    } else if (!through) {
      EXPECT_NE(c.left_free_because, "freed: the map with it pinned was not valid there");
    }
    if (c.enforced) {
      EXPECT_LT(c.max_deviation, 1e-9 * (1 + std::abs(c.value)));
    }
  }
  EXPECT_GE(freed_lines, 1);
  EXPECT_LE(freed.diagnostics.rounding.curve_lines, all.diagnostics.rounding.curve_lines - freed_lines);
  EXPECT_TRUE(measure_seams(mesh, freed.uv, 1e-9).seamless);
  options.alignment.free_line_vertices = {mesh.num_vertices()};
  EXPECT_THROW(parameterize(mesh, field, options), InputError);
}

}  // namespace
}  // namespace quadcover
