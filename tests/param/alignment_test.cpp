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
  bool all_exact;  // no curve runs between two branch points or closes on itself inconsistently
};

class WithCurves : public ::testing::TestWithParam<Case> {};

// The constrained final solve keeps every transition exact, minimizes the same energy under more constraints (so E_H
// can only grow, E_D is unchanged), and puts the curves on integer iso-lines: exactly, except where a curve meets a
// branch point whose position the periods fixed elsewhere or closes on itself with another integer.
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
  int edges = 0, exact_edges = 0, on_line = 0;
  for (const auto& c : P.aligned_curves) {
    EXPECT_EQ(c.value, std::round(c.value));
    edges += static_cast<int>(c.edges.size());
    if (c.max_deviation < 1e-9 * (1 + std::abs(c.value))) exact_edges += static_cast<int>(c.edges.size());
    for (std::size_t i = 0; i < c.edges.size(); ++i) {  // locally: both endpoints on the edge's integer line
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
  if (GetParam().all_exact) {
    EXPECT_EQ(exact_edges, edges);
    EXPECT_EQ(on_line, edges);
    EXPECT_EQ(P.alignment_conflicts, 0);
  } else {
    EXPECT_GE(on_line, 0.8 * edges) << "exact curves cover " << exact_edges << " of " << edges << " edges";
  }
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
                         ::testing::Values(Case{"camelhead_boundary", true}, Case{"bunny_20k_holes", true},
                                           Case{"lilium_disk", false}, Case{"mech_holes_shark", false},
                                           Case{"fandisk", false}),
                         [](const auto& info) { return std::string(info.param.mesh); });

}  // namespace
}  // namespace quadcover
