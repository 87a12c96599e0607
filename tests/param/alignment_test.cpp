// Boundary and feature curves on integer iso-lines (param/alignment.h), with the seams kept exact.
#include "param/alignment.h"

#include <gtest/gtest.h>

#include "field/compute_frame_field.h"
#include "param/parameterize.h"
#include "param/seams.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

struct Case {
  const char* mesh;
  double min_enforced;  // fraction of curve edges on enforced lines (lilium: one boundary loop closing inconsistently)
};

class WithCurves : public ::testing::TestWithParam<Case> {};

// The constrained final solve keeps every transition exact, minimizes the same energy under more constraints (so E_H
// can only grow, E_D is unchanged), and puts the enforced curves exactly on integer iso-lines (lines through two
// branch points at different integers, closing on themselves with another integer, or far from any integer are
// left free and only reported).
TEST_P(WithCurves, CurvesLieOnIntegerIsoLines) {
  const Mesh mesh = testing::load_test_mesh(GetParam().mesh);
  const FrameField field = compute_frame_field(mesh);
  ParamOptions free_opt;
  free_opt.align_curves = false;
  const Parameterization F = parameterize(mesh, field, free_opt);
  const Parameterization P = parameterize(mesh, field);
  ASSERT_FALSE(P.aligned_curves.empty());
  EXPECT_TRUE(F.aligned_curves.empty());
  EXPECT_TRUE(measure_seams(mesh, P.uv, 1e-9).seamless);
  EXPECT_NEAR(P.energy_curl, F.energy_curl, 1e-12 * F.energy_curl);
  EXPECT_GE(P.energy_harmonic, F.energy_harmonic * (1 - 1e-12));
  // Every enforced line is exactly on its integer iso-line, edge by edge (both endpoints, in the edge's face).
  int edges = 0, enforced_edges = 0, on_line = 0;
  for (const auto& c : P.aligned_curves) {
    EXPECT_EQ(c.value, std::round(c.value));
    edges += static_cast<int>(c.edges.size());
    if (!c.enforced) continue;
    enforced_edges += static_cast<int>(c.edges.size());
    EXPECT_LT(c.max_deviation, 1e-9 * (1 + std::abs(c.value)));
    for (std::size_t i = 0; i < c.edges.size(); ++i) {
      const int e = c.edges[i];
      EXPECT_EQ(c.edge_values[i], std::round(c.edge_values[i]));
      const int f = mesh.EF()(e, 0) >= 0 ? mesh.EF()(e, 0) : mesh.EF()(e, 1);
      double x[2];
      for (int end = 0; end < 2; ++end) {
        int k = 0;
        while (mesh.F()(f, k) != mesh.E()(e, end)) ++k;
        x[end] = c.edge_coordinates[i] == 0 ? P.uv(f, k).real() : P.uv(f, k).imag();
      }
      const double tol = 1e-9 * (1 + std::abs(c.edge_values[i]));
      on_line += std::abs(x[0] - c.edge_values[i]) < tol && std::abs(x[1] - c.edge_values[i]) < tol;
    }
  }
  EXPECT_EQ(on_line, enforced_edges);
  EXPECT_GE(enforced_edges, GetParam().min_enforced * edges) << GetParam().mesh;
  // Without alignment the same curves are generally off the integer lines.
  int off = 0;
  for (const auto& c : P.aligned_curves)
    for (std::size_t i = 0; i < c.edges.size(); ++i) {
      const int e = c.edges[i];
      const int f = mesh.EF()(e, 0) >= 0 ? mesh.EF()(e, 0) : mesh.EF()(e, 1);
      for (int k = 0; k < 3; ++k) {
        const double x = c.edge_coordinates[i] == 0 ? F.uv(f, k).real() : F.uv(f, k).imag();
        off += std::abs(x - std::round(x)) > 1e-3;
      }
    }
  EXPECT_GT(off, 0);
}

INSTANTIATE_TEST_SUITE_P(Meshes, WithCurves,
                         ::testing::Values(Case{"camelhead_boundary", 0.3}, Case{"bunny_20k_holes", 0.3},
                                           Case{"lilium_disk", 0.0}, Case{"mech_holes_shark", 0.3},
                                           Case{"fandisk", 0.3}),
                         [](const auto& info) { return std::string(info.param.mesh); });

}  // namespace
}  // namespace quadcover
