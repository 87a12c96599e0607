// The harmonic correction on the covering (thesis 1.2.5 on M̃, (1.14), 4.2.1), checked by direct recomputation:
// H̃ = Σ − ∇u is L²-orthogonal to the gradient of every conforming covering function (0 at branch points), so ∇u
// is the closest gradient; gradients are reproduced (their harmonic part is 0); 𝔏̄ u = b holds off the pins; the
// right-hand side is additive over faces and is ⟨∇φ_p, Σ⟩ (b = 𝔏̄ w for Σ = ∇w). On real meshes and on generated
// ones with many close branch points (random cross fields) and boundary.
#include "param/harmonic_correction.h"

#include <gtest/gtest.h>

#include <random>

#include "common/errors.h"
#include "cover/field_helpers.h"
#include "field/compute_frame_field.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

struct HarmonicCase {
  std::string name;
  Mesh mesh;
  FrameField field;
};

std::vector<HarmonicCase> cases() {
  std::vector<HarmonicCase> out;
  for (const char* name : {"eight_genus2", "lilium_disk"}) {
    Mesh m = testing::load_test_mesh(name);
    FrameField f = compute_frame_field(m);
    out.push_back({name, std::move(m), std::move(f)});
  }
  Mesh torus = testing::make_torus(16, 8);
  FrameField rf = testing::random_cross_field(torus, 4);
  out.push_back({"random torus", std::move(torus), std::move(rf)});
  Mesh cyl = testing::make_cylinder(12, 5);
  FrameField cf = testing::random_cross_field(cyl, 9);
  out.push_back({"random cylinder", std::move(cyl), std::move(cf)});
  return out;
}

// Trivial holonomy per component (as parameterize() decides it): gauged matching ≡ 0 mod 4 and no branch point.
std::vector<char> trivial_holonomy(const Mesh& mesh, const CoverCut& cc) {
  std::vector<char> trivial(static_cast<std::size_t>(mesh.num_components()), 1);
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (!mesh.is_boundary_edge(e) && ((cc.matching[e] % 4) + 4) % 4 != 0)
      trivial[mesh.face_component()[mesh.EF()(e, 0)]] = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (cc.branch[v]) trivial[mesh.vertex_component()[v]] = 0;
  return trivial;
}

FramePairs random_field(int nf, std::mt19937& rng) {
  std::normal_distribution<double> n;
  FramePairs S(nf, 2);
  for (int f = 0; f < nf; ++f) S.row(f) << Complex(n(rng), n(rng)), Complex(n(rng), n(rng));
  return S;
}

// A random conforming covering function: 0 at branch points and at the kernel pins.
Eigen::VectorXcd random_vertex_function(const HarmonicCorrection& hc, int nv, std::mt19937& rng) {
  std::normal_distribution<double> n;
  Eigen::VectorXcd w(nv);
  for (int p = 0; p < nv; ++p) w[p] = hc.layers().branch[p] ? Complex(0) : Complex(n(rng), n(rng));
  for (int p : hc.kernel_pins()) w[p] = 0;
  return w;
}

TEST(HarmonicCorrection, HarmonicPartIsOrthogonalToEveryConformingGradient) {
  std::mt19937 rng(1);
  for (const HarmonicCase& c : cases()) {
    SCOPED_TRACE(c.name);
    const Mesh& mesh = c.mesh;
    const CoverCut cc = build_cover_cut(mesh, c.field.matching);
    const HarmonicCorrection hc(mesh, cc, trivial_holonomy(mesh, cc));
    const FramePairs Sigma = random_field(mesh.num_faces(), rng);
    const FramePairs H = hc.harmonic_part(Sigma);
    const double scale = frame_norm2(mesh, Sigma);
    for (int trial = 0; trial < 3; ++trial) {
      const FramePairs G =
          corner_gradient(mesh, hc.corner_values(random_vertex_function(hc, mesh.num_vertices(), rng)));
      // ⟨H, ∇w⟩ and ⟨H, ∇(i w)⟩ (the real inner product: both real components of the complex coefficient).
      const FramePairs iG =
          corner_gradient(mesh, hc.corner_values(Complex(0, 1) * random_vertex_function(hc, mesh.num_vertices(), rng)));
      const double g = std::sqrt(frame_norm2(mesh, G) * scale), ig = std::sqrt(frame_norm2(mesh, iG) * scale);
      EXPECT_LT(std::abs(frame_inner(mesh, H, G)), 1e-9 * g);
      EXPECT_LT(std::abs(frame_inner(mesh, H, iG)), 1e-9 * ig);
      // Hence ∇u is the closest gradient: moving u by any w only adds ‖∇w‖².
      const double d0 = frame_norm2(mesh, H), d1 = frame_norm2(mesh, H - 0.1 * G);
      EXPECT_NEAR(d1 - d0, 0.01 * frame_norm2(mesh, G), 1e-9 * scale);
    }
  }
}

TEST(HarmonicCorrection, GradientsHaveNoHarmonicPartAndRhsIsTheStiffness) {
  std::mt19937 rng(2);
  for (const HarmonicCase& c : cases()) {
    SCOPED_TRACE(c.name);
    const Mesh& mesh = c.mesh;
    const CoverCut cc = build_cover_cut(mesh, c.field.matching);
    const HarmonicCorrection hc(mesh, cc, trivial_holonomy(mesh, cc));
    const Eigen::VectorXcd w = random_vertex_function(hc, mesh.num_vertices(), rng);
    const FramePairs G = corner_gradient(mesh, hc.corner_values(w));
    // b_p = ⟨∇φ_p, ∇w⟩ = (𝔏̄ w)_p at every vertex off B.
    const Eigen::VectorXcd b = hc.rhs(G), Lw = hc.stiffness() * w;
    for (int p = 0; p < mesh.num_vertices(); ++p)
      if (!hc.layers().branch[p]) {
        EXPECT_LT(std::abs(b[p] - Lw[p]), 1e-9 * (1 + Lw.cwiseAbs().maxCoeff())) << p;
      }
    // The solve reproduces w (pins included: w is 0 there), so the harmonic part of a gradient vanishes.
    const Eigen::VectorXcd u = hc.solve(b).col(0);
    EXPECT_LT((u - w).cwiseAbs().maxCoeff(), 1e-7 * (1 + w.cwiseAbs().maxCoeff()));
    EXPECT_LT(frame_norm2(mesh, hc.harmonic_part(G)), 1e-12 * frame_norm2(mesh, G));
  }
}

TEST(HarmonicCorrection, SolveMeetsTheEquationsAndRhsIsAdditiveOverFaces) {
  std::mt19937 rng(3);
  for (const HarmonicCase& c : cases()) {
    SCOPED_TRACE(c.name);
    const Mesh& mesh = c.mesh;
    const int nf = mesh.num_faces();
    const CoverCut cc = build_cover_cut(mesh, c.field.matching);
    const HarmonicCorrection hc(mesh, cc, trivial_holonomy(mesh, cc));
    const FramePairs Sigma = random_field(nf, rng);
    const Eigen::VectorXcd b = hc.rhs(Sigma);
    // Two columns at once, each meeting 𝔏̄ u = b off the pinned rows (branch points and kernel pins: u = 0).
    Eigen::MatrixXcd B(b.size(), 2);
    B << b, Complex(0, 1) * b;
    const Eigen::MatrixXcd U = hc.solve(B);
    std::vector<char> pinned(static_cast<std::size_t>(mesh.num_vertices()), 0);
    for (int p : hc.kernel_pins()) pinned[p] = 1;
    for (int k = 0; k < 2; ++k) {
      const Eigen::VectorXcd r = hc.stiffness() * U.col(k) - B.col(k);
      for (int p = 0; p < mesh.num_vertices(); ++p) {
        if (hc.layers().branch[p] || pinned[p]) {
          EXPECT_LT(std::abs(U(p, k)), 1e-12);
          continue;
        }
        EXPECT_LT(std::abs(r[p]), 1e-8 * (1 + b.cwiseAbs().maxCoeff())) << p;
      }
    }
    EXPECT_LT((U.col(1) - Complex(0, 1) * U.col(0)).cwiseAbs().maxCoeff(), 1e-9 * (1 + U.cwiseAbs().maxCoeff()));
    // rhs over the even faces + rhs over the odd faces (also in the sparse X/Y form) = rhs over all.
    std::vector<int> even, odd;
    std::vector<Complex> X, Y;
    for (int f = 0; f < nf; ++f) {
      (f % 2 ? odd : even).push_back(f);
      if (f % 2) X.push_back(Sigma(f, 0)), Y.push_back(Sigma(f, 1));
    }
    const Eigen::VectorXcd sum = hc.rhs(Sigma, even) + hc.rhs(odd, X, Y);
    EXPECT_LT((sum - b).cwiseAbs().maxCoeff(), 1e-12 * (1 + b.cwiseAbs().maxCoeff()));
  }
}

TEST(HarmonicCorrection, ReleasedFactorRefusesToSolveAndKeepsTheRest) {
  const Mesh mesh = testing::load_test_mesh("eight_genus2");
  const FrameField field = compute_frame_field(mesh);
  const CoverCut cc = build_cover_cut(mesh, field.matching);
  HarmonicCorrection hc(mesh, cc, trivial_holonomy(mesh, cc));
  std::mt19937 rng(5);
  const FramePairs Sigma = random_field(mesh.num_faces(), rng);
  const Eigen::VectorXcd b = hc.rhs(Sigma);
  const Eigen::VectorXcd u = hc.solve(b).col(0);
  const Eigen::MatrixX3cd corners = hc.corner_values(u);
  const Eigen::SparseMatrix<Complex> L = hc.stiffness();
  hc.release_factor();
  EXPECT_THROW(hc.solve(b), NumericalError);
  EXPECT_THROW(hc.harmonic_part(Sigma), NumericalError);
  // What does not need the factor is unchanged.
  EXPECT_EQ((hc.rhs(Sigma) - b).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((hc.corner_values(u) - corners).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(Eigen::MatrixXcd(hc.stiffness() - L).cwiseAbs().maxCoeff(), 0.0);
}

TEST(HarmonicCorrection, PinRowsAndFrameNorm) {
  const Mesh mesh = testing::make_torus(8, 5);
  const CoverCut cc = build_cover_cut(mesh, Eigen::VectorXi::Zero(mesh.num_edges()));
  Eigen::SparseMatrix<Complex> A = complex_conforming_stiffness(mesh, cc.matching);
  const Eigen::MatrixXcd before(A);
  pin_rows(A, {0, 3});
  const Eigen::MatrixXcd after(A);
  for (int i = 0; i < after.rows(); ++i)
    for (int j = 0; j < after.cols(); ++j) {
      const bool p = i == 0 || i == 3 || j == 0 || j == 3;
      EXPECT_EQ(after(i, j), p ? Complex(i == j ? 1 : 0) : before(i, j)) << i << "," << j;
    }
  std::mt19937 rng(4);
  const FramePairs Z = random_field(mesh.num_faces(), rng), W = random_field(mesh.num_faces(), rng);
  double direct = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) direct += mesh.face_areas()[f] * (std::norm(Z(f, 0)) + std::norm(Z(f, 1)));
  EXPECT_NEAR(frame_norm2(mesh, Z), direct, 1e-12 * direct);
  EXPECT_NEAR(frame_inner(mesh, Z, Z), direct, 1e-12 * direct);
  // Polarization: ⟨Z, W⟩ = (‖Z + W‖² − ‖Z − W‖²) / 4.
  EXPECT_NEAR(frame_inner(mesh, Z, W), 0.25 * (frame_norm2(mesh, Z + W) - frame_norm2(mesh, Z - W)), 1e-10 * direct);
}

}  // namespace
}  // namespace quadcover
