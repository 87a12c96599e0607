// Complex Hermitian stiffness matrices 𝔏̄*, 𝔏̄ (3.8) and the complex curl* (3.3), checked on real meshes.
#include "cover/complex_stiffness.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <random>
#include <set>

#include "cover/field_helpers.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

using testing::load_test_mesh;

class OnRealMeshes : public ::testing::TestWithParam<const char*> {};

// J∇v per face (frame pair (X-part, Y-part)) of a covering nonconforming function v given in reference gauge.
std::pair<Eigen::VectorXcd, Eigen::VectorXcd> rotated_gradient(const Mesh& mesh, const Eigen::MatrixX3i& mu,
                                                               const Eigen::VectorXcd& v) {
  Eigen::VectorXcd X = Eigen::VectorXcd::Zero(mesh.num_faces()), Y = X;
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Complex w = ipow(mu(f, k)) * v[mesh.FE()(f, k)];  // local value
      const Complex e = mesh.edge_vector_local(f, k) / mesh.face_areas()[f];  // J∇ψ = e / A
      X[f] += w.real() * e;
      Y[f] += w.imag() * e;
    }
  return {X, Y};
}

Eigen::VectorXi random_quarter_turns(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> d(-3, 3);
  Eigen::VectorXi r(n);
  for (int i = 0; i < n; ++i) r[i] = d(rng);
  return r;
}

int reference_face(const Mesh& mesh, int e) {
  const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
  return s < 0 ? t : (t < 0 ? s : std::min(s, t));
}

// 𝔏̄* is Hermitian and has exactly the pattern of 𝔏* (edges sharing a face) whatever the matching.
TEST_P(OnRealMeshes, NonconformingIsHermitianWithFixedPattern) {
  const Mesh mesh = load_test_mesh(GetParam());
  const FrameField field = testing::random_frame_field(mesh, 7);
  const Eigen::SparseMatrix<Complex> L = complex_nonconforming_stiffness(mesh, field.matching);
  const Eigen::SparseMatrix<Complex> L0 =
      complex_nonconforming_stiffness(mesh, Eigen::VectorXi::Zero(mesh.num_edges()));
  const Eigen::SparseMatrix<Complex> LH = L.adjoint();
  EXPECT_LT((L - LH).norm(), 1e-12 * L.norm());
  std::set<std::pair<int, int>> expected;
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) expected.insert({mesh.FE()(f, a), mesh.FE()(f, b)});
  for (const auto* M : {&L, &L0}) {
    std::set<std::pair<int, int>> got;
    for (int c = 0; c < M->outerSize(); ++c)
      for (Eigen::SparseMatrix<Complex>::InnerIterator it(*M, c); it; ++it) got.insert({int(it.row()), int(it.col())});
    EXPECT_EQ(got, expected);
  }
  // Entry moduli are those of 𝔏* (3.8): |𝔏̄*_ij| = |𝔏*_ij| (off-diagonal entries have one face in common).
  for (int c = 0; c < L.outerSize(); ++c)
    for (Eigen::SparseMatrix<Complex>::InnerIterator it(L, c); it; ++it)
      EXPECT_NEAR(std::abs(it.value()), std::abs(L0.coeff(it.row(), it.col())), 1e-9 * (1 + std::abs(it.value())));
}

// With zero matching 𝔏̄* is the real Crouzeix–Raviart matrix (1.5): -2 cot of the angle at the common vertex.
TEST_P(OnRealMeshes, ZeroMatchingGivesRealCotanMatrices) {
  const Mesh mesh = load_test_mesh(GetParam());
  const Eigen::VectorXi zero = Eigen::VectorXi::Zero(mesh.num_edges());
  const Eigen::SparseMatrix<Complex> Ls = complex_nonconforming_stiffness(mesh, zero);
  const Eigen::SparseMatrix<Complex> L = complex_conforming_stiffness(mesh, zero);
  Eigen::SparseMatrix<double> Cs(mesh.num_edges(), mesh.num_edges()), C(mesh.num_vertices(), mesh.num_vertices());
  std::vector<Eigen::Triplet<double>> ts, tc;
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const double cot = mesh.corner_cotangents()(f, c);
      const int a = mesh.FE()(f, (c + 1) % 3), b = mesh.FE()(f, (c + 2) % 3);  // the two edges at corner c
      ts.insert(ts.end(), {{a, b, -2 * cot}, {b, a, -2 * cot}, {a, a, 2 * cot}, {b, b, 2 * cot}});
      const int p = mesh.F()(f, (c + 1) % 3), q = mesh.F()(f, (c + 2) % 3);  // the edge opposite corner c
      tc.insert(tc.end(), {{p, q, -0.5 * cot}, {q, p, -0.5 * cot}, {p, p, 0.5 * cot}, {q, q, 0.5 * cot}});
    }
  Cs.setFromTriplets(ts.begin(), ts.end());
  C.setFromTriplets(tc.begin(), tc.end());
  EXPECT_LT((Eigen::SparseMatrix<double>(Ls.imag()).norm()), 1e-14 * Ls.norm());
  EXPECT_LT((Eigen::SparseMatrix<double>(Ls.real()) - Cs).norm(), 1e-9 * Cs.norm());
  EXPECT_LT((Eigen::SparseMatrix<double>(L.real()) - C).norm(), 1e-9 * C.norm());
}

// A change of the per-face gauge Z_f -> i^{r_f} Z_f changes the matching by r_s - r_t and acts on 𝔏̄*, 𝔏̄ and curl*
// by the diagonal unitary D = diag(i^{r_ref}): 𝔏̄*' = D 𝔏̄* Dᴴ, curl*' = D curl*.
TEST_P(OnRealMeshes, GaugeCovariance) {
  const Mesh mesh = load_test_mesh(GetParam());
  const FrameField field = testing::random_frame_field(mesh, 11);
  const Eigen::VectorXi r = random_quarter_turns(mesh.num_faces(), 5);
  FrameField turned = field;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    Complex x = field.X[f], y = field.Y[f];
    for (int k = 0; k < ((r[f] % 4) + 4) % 4; ++k) std::tie(x, y) = std::pair<Complex, Complex>(-y, x);  // i·(X+iY)
    turned.X[f] = x;
    turned.Y[f] = y;
  }
  turned.matching = field.matching + testing::gauge_matching(mesh, r);
  Eigen::VectorXcd D(mesh.num_edges());
  for (int e = 0; e < mesh.num_edges(); ++e) D[e] = ipow(r[reference_face(mesh, e)]);
  const Eigen::SparseMatrix<Complex> L = complex_nonconforming_stiffness(mesh, field.matching);
  const Eigen::SparseMatrix<Complex> Lt = complex_nonconforming_stiffness(mesh, turned.matching);
  const Eigen::SparseMatrix<Complex> expected = D.asDiagonal() * L * D.conjugate().asDiagonal();
  EXPECT_LT((Lt - expected).norm(), 1e-12 * L.norm());
  const Eigen::VectorXcd curl = complex_curl_star(mesh, field);
  EXPECT_LT((complex_curl_star(mesh, turned) - D.asDiagonal() * curl).norm(), 1e-12 * curl.norm());
}

// Trivial holonomy (a pure gauge matching): the covering constants i^{r_f}·c lie in the kernel of 𝔏̄* and 𝔏̄.
TEST_P(OnRealMeshes, GaugeConstantsAreHarmonic) {
  const Mesh mesh = load_test_mesh(GetParam());
  const Eigen::VectorXi r = random_quarter_turns(mesh.num_faces(), 3);
  const Eigen::VectorXi m = testing::gauge_matching(mesh, r);
  const Complex c(0.6, -1.3);
  Eigen::VectorXcd ue(mesh.num_edges());
  for (int e = 0; e < mesh.num_edges(); ++e) ue[e] = ipow(r[reference_face(mesh, e)]) * c;
  const Eigen::SparseMatrix<Complex> Ls = complex_nonconforming_stiffness(mesh, m);
  EXPECT_LT((Ls * ue).norm(), 1e-10 * Ls.norm() * ue.norm());
  const VertexLayers vl = vertex_layers(mesh, m);
  EXPECT_EQ(vl.branch.sum(), 0);
  Eigen::VectorXcd uv(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    int best = std::numeric_limits<int>::max();
    for (const auto& fc : mesh.fan(v)) best = std::min(best, fc.face);
    uv[v] = ipow(r[best]) * c;
  }
  const Eigen::SparseMatrix<Complex> L = complex_conforming_stiffness(mesh, m);
  EXPECT_LT((L * uv).norm(), 1e-10 * L.norm() * uv.norm());
}

// Curl removal on the covering, (2.1) with 𝔏̄* and curl* (3.3): the remainder X̂ = Z - J∇v is curl*-free.
TEST_P(OnRealMeshes, CurlRemovalLeavesCurlFreeField) {
  const Mesh mesh = load_test_mesh(GetParam());
  for (const FrameField& field : {testing::random_cross_field(mesh, 1), testing::smooth_cross_field(mesh)}) {
    const Eigen::VectorXcd curl = complex_curl_star(mesh, field);
    Eigen::SparseMatrix<Complex> L = complex_nonconforming_stiffness(mesh, field.matching);
    const double eps = 1e-11 * L.diagonal().real().mean();
    for (int e = 0; e < mesh.num_edges(); ++e) L.coeffRef(e, e) += eps;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<Complex>> solver(L);
    ASSERT_EQ(solver.info(), Eigen::Success);
    const Eigen::VectorXcd v = solver.solve(-curl);
    const auto [JX, JY] = rotated_gradient(mesh, edge_layers(mesh, field.matching), v);
    FrameField rest = field;
    rest.X = field.X - JX;
    rest.Y = field.Y - JY;
    EXPECT_LT(complex_curl_star(mesh, rest).norm(), 1e-8 * curl.norm()) << GetParam();
    EXPECT_GT(curl.norm(), 1e-3);  // the input field was not curl-free: the test is not vacuous
  }
}

// The covering gradient of a conforming covering function (vertex gauges, zero at branch points) is curl*-free on
// interior edges, and its energy is the quadratic form of 𝔏̄.
TEST_P(OnRealMeshes, GradientsOfCoveringFunctionsAreCurlFree) {
  const Mesh mesh = load_test_mesh(GetParam());
  const FrameField field = testing::random_cross_field(mesh, 2);
  const VertexLayers vl = vertex_layers(mesh, field.matching);
  EXPECT_GT(vl.branch.sum(), 0);
  std::mt19937 rng(4);
  std::normal_distribution<double> g(0, 1);
  Eigen::VectorXcd u(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) u[v] = vl.branch[v] ? Complex(0) : Complex(g(rng), g(rng));
  FrameField grad = field;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    grad.X[f] = grad.Y[f] = 0;
    for (int k = 0; k < 3; ++k) {
      const Complex w = ipow(vl.layer(f, k)) * u[mesh.F()(f, k)];
      const Complex Je = Complex(0, 1) * mesh.edge_vector_local(f, k) / (2 * mesh.face_areas()[f]);
      grad.X[f] += w.real() * Je;
      grad.Y[f] += w.imag() * Je;
    }
  }
  Eigen::VectorXcd curl = complex_curl_star(mesh, grad);
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (mesh.is_boundary_edge(e)) curl[e] = 0;  // one-sided: ⟨e, ∇u⟩, not a curl
  double scale = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) scale += std::abs(grad.X[f]) * mesh.mean_edge_length();
  EXPECT_LT(curl.norm(), 1e-10 * scale);
  // Energy identity: uᴴ 𝔏̄ u = ‖∇u‖² (both layers).
  const Eigen::SparseMatrix<Complex> L = complex_conforming_stiffness(mesh, field.matching);
  double energy = 0;
  for (int f = 0; f < mesh.num_faces(); ++f)
    energy += mesh.face_areas()[f] * (std::norm(grad.X[f]) + std::norm(grad.Y[f]));
  const Complex quad = u.dot(L * u);
  EXPECT_NEAR(quad.real(), energy, 1e-9 * energy);
  EXPECT_NEAR(quad.imag(), 0.0, 1e-9 * energy);
}

// 𝔏̄ has the pattern of 𝔏 whatever the matching (so one symbolic analysis or ordering serves every field on the
// mesh), while the rows and columns of branch points hold only their unit diagonal.
TEST_P(OnRealMeshes, ConformingPatternIsTheMeshesForEveryMatching) {
  const Mesh mesh = load_test_mesh(GetParam());
  const Eigen::VectorXi zero = Eigen::VectorXi::Zero(mesh.num_edges());
  const FrameField field = testing::random_cross_field(mesh, 3);
  const VertexLayers vl = vertex_layers(mesh, field.matching);
  ASSERT_GT(vl.branch.sum(), 0);
  const Eigen::SparseMatrix<Complex> plain = complex_conforming_stiffness(mesh, zero);
  const Eigen::SparseMatrix<Complex> L = complex_conforming_stiffness(mesh, field.matching);
  ASSERT_EQ(L.nonZeros(), plain.nonZeros());
  EXPECT_TRUE(std::equal(L.outerIndexPtr(), L.outerIndexPtr() + L.outerSize() + 1, plain.outerIndexPtr()));
  EXPECT_TRUE(std::equal(L.innerIndexPtr(), L.innerIndexPtr() + L.nonZeros(), plain.innerIndexPtr()));
  int branch_entries = 0;
  for (int col = 0; col < L.outerSize(); ++col)
    for (Eigen::SparseMatrix<Complex>::InnerIterator it(L, col); it; ++it)
      if (vl.branch[it.row()] || vl.branch[it.col()]) {
        EXPECT_EQ(it.value(), it.row() == it.col() ? Complex(1) : Complex(0));
        ++branch_entries;
      }
  EXPECT_GT(branch_entries, 2 * vl.branch.sum());  // their neighbours' entries are stored too
}

INSTANTIATE_TEST_SUITE_P(Meshes, OnRealMeshes,
                         ::testing::Values("bunny_3k", "torus_5k", "eight_genus2", "lilium_disk", "fertility_genus4"));

}  // namespace
}  // namespace quadcover
