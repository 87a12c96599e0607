// Untangling of the final map (param/untangle.h): the per-face energy and its derivatives, untangling a deliberately
// folded seamless map inside its affine subspace on real meshes (seams, branch points and the fixed components
// exact), and the default parameterize() on generated hard cases and shipped meshes.
#include "param/untangle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <numbers>
#include <random>
#include <string>

#include "field/compute_frame_field.h"
#include "map_checks.h"
#include "param/cover_cut.h"
#include "param/parameterize.h"
#include "param/seams.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

Eigen::Vector4d vec(const Eigen::Matrix2d& J) { return {J(0, 0), J(0, 1), J(1, 0), J(1, 1)}; }
Eigen::Matrix2d mat(const Eigen::Vector4d& v) { return (Eigen::Matrix2d() << v[0], v[1], v[2], v[3]).finished(); }

// Central differences of f_ε and of its gradient, on folded and unfolded Jacobians.
TEST(UntangleDensity, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0, 1);
  for (int trial = 0; trial < 40; ++trial) {
    Eigen::Matrix2d J;
    J << n(rng), n(rng), n(rng), n(rng);
    const double eps = trial % 2 ? 0.3 : 1e-2, lambda = 0.5 + trial % 3;
    Eigen::Vector4d g;
    Eigen::Matrix4d H;
    untangle_density(J, eps, lambda, &g, &H);
    const double h = 1e-6;
    for (int k = 0; k < 4; ++k) {
      Eigen::Vector4d dp = vec(J), dm = vec(J);
      dp[k] += h, dm[k] -= h;
      const double fd = (untangle_density(mat(dp), eps, lambda) - untangle_density(mat(dm), eps, lambda)) / (2 * h);
      EXPECT_NEAR(g[k], fd, 1e-5 * (1 + std::abs(fd))) << J << " eps " << eps;
      Eigen::Vector4d gp, gm;
      untangle_density(mat(dp), eps, lambda, &gp);
      untangle_density(mat(dm), eps, lambda, &gm);
      const Eigen::Vector4d hd = (gp - gm) / (2 * h);
      for (int l = 0; l < 4; ++l) EXPECT_NEAR(H(l, k), hd[l], 1e-4 * (1 + std::abs(hd[l]))) << J;
    }
  }
}

// ε = 0: the barrier is infinite on mirrored and degenerate Jacobians and minimal (2 + 2λ) on rotations.
TEST(UntangleDensity, BarrierAndMinimum) {
  Eigen::Matrix2d mirror = Eigen::Matrix2d::Identity();
  mirror(1, 1) = -1;
  EXPECT_TRUE(std::isinf(untangle_density(mirror, 0, 1)));
  EXPECT_TRUE(std::isinf(untangle_density(Eigen::Matrix2d::Zero(), 0, 1)));
  EXPECT_TRUE(std::isfinite(untangle_density(mirror, 1e-3, 1)));
  Eigen::Matrix2d R;
  R << std::cos(0.4), -std::sin(0.4), std::sin(0.4), std::cos(0.4);
  EXPECT_NEAR(untangle_density(R, 0, 0.7), 2 + 2 * 0.7, 1e-12);
  EXPECT_GT(untangle_density(1.1 * R, 0, 0.7), 2 + 2 * 0.7);
  Eigen::Matrix2d S = R;
  S(0, 1) += 0.05;
  EXPECT_GT(untangle_density(S, 0, 0.7), 2 + 2 * 0.7);
}

// A seamless map φ = P.uv − corner_values(u0) with a random covering function u0 (0 at branch points, so every
// transition, period and cone position is that of P.uv) folds everywhere; the untangler unfolds it without moving
// anything it must not move.
struct FoldedCase {
  const char* mesh;
  int quads;   ///< target quad count (0: the default density)
  bool clean;  ///< no two adjacent branch points on one integer point: every triangle must end positive
};

class FoldedMaps : public ::testing::TestWithParam<FoldedCase> {};

TEST_P(FoldedMaps, UntanglesInsideTheSeamlessSubspace) {
  const Mesh mesh = testing::load_test_mesh(GetParam().mesh);
  const FrameField field = compute_frame_field(mesh);
  ParamOptions options;
  options.alignment.enabled = false;
  options.density.target_quads = GetParam().quads;
  const Parameterization P = parameterize(mesh, field, options);
  const CoverCut cc = build_cover_cut(mesh, field.matching);
  const HarmonicCorrection correction(mesh, cc, std::vector<char>(mesh.num_components(), 0));
  FramePairs Z(mesh.num_faces(), 2);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto [x, y] = turn_frame(field.X[f], field.Y[f], cc.face_rotation[f]);
    Z(f, 0) = P.scale * x, Z(f, 1) = P.scale * y;
  }
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 0.3 * mesh.mean_edge_length() / P.edge_length);  // grid units
  Eigen::VectorXcd u0(mesh.num_vertices());
  for (int p = 0; p < mesh.num_vertices(); ++p) u0[p] = Complex(noise(rng), noise(rng));
  // A few vertices pinned at their perturbed values, as curve constraints would pin one component.
  std::vector<char> given(2 * mesh.num_vertices(), 0);
  for (int p = 0; p < mesh.num_vertices(); p += 97) given[p] = 1;
  const std::vector<char> fixed = untangle_fixed_components(mesh, correction.layers(), {}, given);
  ParamDiagnostics::Untangling report;
  const Eigen::VectorXcd u = untangle_map(mesh, correction, P.uv, Z, fixed, u0, {}, null_progress(), report);
  Parameterization Q = P;
  Q.uv = P.uv - correction.corner_values(u);
  const Eigen::MatrixX3cd folded = P.uv - correction.corner_values(u0);
  EXPECT_GT(flipped_triangles(mesh, folded).non_positive, mesh.num_faces() / 50);
  EXPECT_EQ(report.non_positive_before, flipped_triangles(mesh, folded).non_positive);
  // Non-positive at the end: only the faces the subspace holds at det 0, i.e. two corners at branch points rounded
  // to one integer point (an edge of length 0).
  const FlipReport after = flipped_triangles(mesh, Q.uv);
  EXPECT_EQ(report.non_positive_after, after.non_positive);
  EXPECT_EQ(after.flipped_faces, report.stuck_faces);
  for (int f : report.stuck_faces) {
    int coincident_branch_pairs = 0;
    for (int c = 0; c < 3; ++c) {
      const int p = mesh.F()(f, c), q = mesh.F()(f, (c + 1) % 3);
      coincident_branch_pairs += correction.layers().branch[p] && correction.layers().branch[q] &&
                                 std::abs(Q.uv(f, c) - Q.uv(f, (c + 1) % 3)) < 1e-9;
    }
    EXPECT_GT(coincident_branch_pairs, 0) << f;
  }
  if (GetParam().clean) {
    EXPECT_EQ(after.non_positive, 0);
  }
  EXPECT_GT(report.min_det, 0);
  EXPECT_GT(report.iterations, 0);
  testing::expect_seamless_grid_map(mesh, Q);  // seams to 1e-9, branch points on their integer points
  const int nv = mesh.num_vertices();
  for (int p = 0; p < nv; ++p) {
    if (fixed[p]) {
      ASSERT_EQ(u[p].real(), u0[p].real()) << p;
    }
    if (fixed[nv + p]) {
      ASSERT_EQ(u[p].imag(), u0[p].imag()) << p;
    }
  }
  // Nothing to do on an injective map: u comes back unchanged.
  ParamDiagnostics::Untangling again;
  const Eigen::VectorXcd w =
      untangle_map(mesh, correction, Q.uv, Z, fixed, Eigen::VectorXcd::Zero(nv), {}, null_progress(), again);
  EXPECT_EQ(again.iterations, 0);
  EXPECT_EQ(again.stuck_faces, report.stuck_faces);
  EXPECT_EQ(w, Eigen::VectorXcd::Zero(nv));
}

INSTANTIATE_TEST_SUITE_P(Meshes, FoldedMaps,
                         ::testing::Values(FoldedCase{"bunny_3k", 0, false}, FoldedCase{"bunny_3k", 6500, false},
                                           FoldedCase{"fertility_genus4", 0, false},
                                           FoldedCase{"fertility_genus4", 6500, true}));

// The default parameterize() untangles what its subspace allows: every triangle left non-positive is one the
// constraints hold at det 0 (stuck) or one no region around it could unfold (unresolved), the count never grows, and
// the seams, cones and curves stay exact.
void expect_untangled(const Mesh& mesh, const Parameterization& P, const std::string& name) {
  const FlipReport flips = flipped_triangles(mesh, P.uv);
  std::vector<int> listed = P.diagnostics.untangling.stuck_faces;
  listed.insert(listed.end(), P.diagnostics.untangling.unresolved_faces.begin(), P.diagnostics.untangling.unresolved_faces.end());
  std::sort(listed.begin(), listed.end());
  if (P.diagnostics.untangling.non_positive_before > 0) {
    EXPECT_EQ(flips.flipped_faces, listed) << name;
    EXPECT_EQ(P.diagnostics.untangling.non_positive_after, flips.non_positive) << name;
    EXPECT_LE(P.diagnostics.untangling.non_positive_after, P.diagnostics.untangling.non_positive_before) << name;
  }
  testing::expect_seamless_grid_map(mesh, P);
  std::cerr << name << ": " << P.diagnostics.untangling.non_positive_before << " -> " << flips.non_positive << " non-positive ("
            << P.diagnostics.untangling.stuck_faces.size() << " stuck, " << P.diagnostics.untangling.unresolved_faces.size() << " unresolved), "
            << P.diagnostics.untangling.iterations << " + " << P.diagnostics.untangling.polish_iterations << " steps, " << P.diagnostics.untangling.seconds
            << " s\n";
}

struct ShippedCase {
  const char* mesh;
  bool clean;  ///< reaches 0 non-positive triangles with the default options
};

class ShippedMeshes : public ::testing::TestWithParam<ShippedCase> {};

TEST_P(ShippedMeshes, DefaultMapIsUntangled) {
  const Mesh mesh = testing::load_test_mesh(GetParam().mesh);
  const Parameterization P = parameterize(mesh, compute_frame_field(mesh));
  expect_untangled(mesh, P, GetParam().mesh);
  if (GetParam().clean) {
    EXPECT_EQ(flipped_triangles(mesh, P.uv).non_positive, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, ShippedMeshes,
                         ::testing::Values(ShippedCase{"eight_genus2", true}, ShippedCase{"bunny_3k", false},
                                           ShippedCase{"couplingdown_genus9", false}, ShippedCase{"torus_5k", true},
                                           ShippedCase{"cow", false}, ShippedCase{"spot", false},
                                           ShippedCase{"lilium_disk", true}, ShippedCase{"3holes_genus3", true},
                                           ShippedCase{"fertility_genus4", false},
                                           ShippedCase{"mech_holes_shark", false}, ShippedCase{"fandisk", false}));

// Generated hard cases: a coarse sphere whose eight cones are a few edges apart, a bipyramid of slivers around two
// valence-24 apexes, a flat ellipsoid of very anisotropic triangles and bunny_3k with every face turned over.
TEST(Untangle, GeneratedHardCases) {
  struct Case {
    std::string name;
    Mesh mesh;
    int quads;
  };
  const Mesh inverted = testing::with_faces_reversed(testing::load_test_mesh("bunny_3k"));
  std::vector<Case> cases;
  cases.push_back({"coarse sphere", testing::make_ellipsoid(1), 40});
  cases.push_back({"coarse sphere, denser grid", testing::make_ellipsoid(2), 60});
  cases.push_back({"sliver bipyramid", testing::make_fan(24, true, 0.05), 30});
  cases.push_back({"flat ellipsoid", testing::make_ellipsoid(3, 1, 1, 0.03), 200});
  cases.push_back({"inverted bunny_3k", inverted, 0});
  for (const Case& c : cases) {
    ParamOptions o;
    o.density.target_quads = c.quads;
    const Parameterization P = parameterize(c.mesh, compute_frame_field(c.mesh), o);
    expect_untangled(c.mesh, P, c.name);
  }
}

// Triangles with three corners on one enforced iso-line (CAD creases, boundary ears) are stuck at det 0; releasing
// the curve constraint at one of their corners lets the untangler open them, seams and cones staying exact.
TEST(Untangle, ReleasingCurveCornersOpensStuckCurveTriangles) {
  for (const char* name : {"couplingdown_genus9", "camelhead_boundary"}) {
    const Mesh mesh = testing::load_test_mesh(name);
    const FrameField field = compute_frame_field(mesh);
    const Parameterization A = parameterize(mesh, field);
    ParamOptions o;
    o.untangle.release_curve_corners = true;
    const Parameterization B = parameterize(mesh, field, o);
    EXPECT_TRUE(A.diagnostics.untangling.released_vertices.empty());
    ASSERT_FALSE(B.diagnostics.untangling.released_vertices.empty()) << name;
    EXPECT_LT(B.diagnostics.untangling.stuck_faces.size(), A.diagnostics.untangling.stuck_faces.size()) << name;
    EXPECT_LT(flipped_triangles(mesh, B.uv).non_positive, flipped_triangles(mesh, A.uv).non_positive) << name;
    EXPECT_TRUE(measure_seams(mesh, B.uv, 1e-9).seamless);
    std::cerr << name << ": " << flipped_triangles(mesh, A.uv).non_positive << " -> "
              << flipped_triangles(mesh, B.uv).non_positive << " non-positive, "
              << B.diagnostics.untangling.released_vertices.size() << " curve vertices released, stuck "
              << A.diagnostics.untangling.stuck_faces.size() << " -> " << B.diagnostics.untangling.stuck_faces.size() << "\n";
  }
}

// The regions grow around folds only while they help: a fold the constraints hold (a fan whose fixed rim crosses
// itself, so some triangle stays non-positive wherever the apex goes) is tried in the first region and the next, not
// in a third; an apex merely put outside its convex rim is untangled in the first region.
TEST(Untangle, RegionsStopGrowingWhenTheConstraintsHoldTheFolds) {
  const Mesh fan = testing::make_fan(6, /*closed=*/false);
  const int nv = fan.num_vertices(), nf = fan.num_faces();
  const VertexLayers layers{Eigen::MatrixX3i::Zero(nf, 3), Eigen::VectorXi::Zero(nv)};
  FramePairs Z(nf, 2);
  Z.col(0).setConstant(Complex(1, 0));
  Z.col(1).setConstant(Complex(0, 1));
  std::vector<char> rim_fixed(static_cast<std::size_t>(2 * nv), 1);
  rim_fixed[0] = rim_fixed[nv] = 0;  // only the apex moves
  for (const bool crossed : {false, true}) {
    SCOPED_TRACE(crossed ? "crossed rim" : "convex rim");
    Eigen::MatrixX3cd base(nf, 3);
    for (int f = 0; f < nf; ++f)
      for (int c = 0; c < 3; ++c) {
        int p = fan.F()(f, c);
        if (crossed && (p == 2 || p == 3)) p = 5 - p;  // rim vertices 2 and 3 swap places
        base(f, c) = p == 0 ? Complex(3, 0) : std::polar(1.0, 2 * std::numbers::pi * (p - 1) / 6);
      }
    ParamDiagnostics::Untangling r;
    const Eigen::VectorXcd u =
        untangle_map(fan, layers, base, Z, rim_fixed, Eigen::VectorXcd::Zero(nv), {}, null_progress(), r);
    ASSERT_GT(r.non_positive_before, 0);
    if (crossed) {
      EXPECT_GT(r.non_positive_after, 0);
      EXPECT_FALSE(r.unresolved_faces.empty());
      EXPECT_EQ(r.regions, 2);
    } else {
      EXPECT_EQ(r.non_positive_after, 0);
      EXPECT_EQ(r.regions, 1);
    }
    for (int p = 1; p < nv; ++p) EXPECT_EQ(u[p], Complex(0)) << p;
  }
}

}  // namespace
}  // namespace quadcover
