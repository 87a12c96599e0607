// Cholesky up/downdates of complex Hermitian "cover" matrices (thesis 6.2.1): after hundreds of random matching
// changes (single edges and branch-point paths) the updated factor and xᴴx equal a fresh factorization.
// The matrices have exactly the structure of 𝔏̄* (3.8): Σ_f D_f K_f D_fᴴ with the Crouzeix–Raviart face stiffness
// K_f and a layer phase i^l per (face, edge), so a matching change at edge e_k in face t multiplies the entries
// (k, l), (k, m) of t by i^{±1} — the four-entry change of 6.2.1.
#include "optimize/updatable_cholesky.h"

#include <cs.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "calculus/sparse_cholesky.h"
#include "common/errors.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

const Complex I{0, 1};

Complex ipow(int l) {
  static const Complex p[4] = {1.0, I, -1.0, -I};
  return p[((l % 4) + 4) % 4];
}

struct SyntheticCover {
  const Mesh& mesh;
  Eigen::MatrixX3i phase;  // layer l of (face, local edge)
  double shift;

  SyntheticCover(const Mesh& m, std::mt19937& rng, double shift_rel = 1e-6) : mesh(m), phase(m.num_faces(), 3) {
    std::uniform_int_distribution<int> d4(0, 3);
    for (int f = 0; f < m.num_faces(); ++f)
      for (int a = 0; a < 3; ++a) phase(f, a) = d4(rng);
    shift = shift_rel * 2.0 * m.corner_cotangents().cwiseAbs().mean();
  }
  // CR face stiffness (1.5): K_ab = -2 cot(angle at the corner shared by edges a and b), rows sum to zero.
  double K(int f, int a, int b) const {
    const auto& cot = mesh.corner_cotangents();
    if (a != b) return -2.0 * cot(f, 3 - a - b);
    return 2.0 * (cot(f, (a + 1) % 3) + cot(f, (a + 2) % 3));
  }
  Eigen::SparseMatrix<Complex> matrix() const {
    std::vector<Eigen::Triplet<Complex>> t;
    for (int f = 0; f < mesh.num_faces(); ++f)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          t.emplace_back(mesh.FE()(f, a), mesh.FE()(f, b), ipow(phase(f, a) - phase(f, b)) * K(f, a, b));
    for (int e = 0; e < mesh.num_edges(); ++e) t.emplace_back(e, e, shift);
    Eigen::SparseMatrix<Complex> A(mesh.num_edges(), mesh.num_edges());
    A.setFromTriplets(t.begin(), t.end());
    return A;
  }
  // Turns the layer of edge slot a in face f by delta quarter turns; returns the change D of the matrix.
  StarChange turn(int f, int a, int delta) {
    StarChange c;
    c.k = mesh.FE()(f, a);
    for (int b = 0; b < 3; ++b) {
      if (b == a) continue;
      const Complex before = ipow(phase(f, a) - phase(f, b)) * K(f, a, b);
      const Complex after = ipow(phase(f, a) + delta - phase(f, b)) * K(f, a, b);
      c.d.push_back({mesh.FE()(f, b), after - before});
    }
    phase(f, a) += delta;
    return c;
  }
};

Eigen::VectorXcd random_vector(int n, std::mt19937& rng) {
  std::normal_distribution<double> g;
  Eigen::VectorXcd v(n);
  for (int i = 0; i < n; ++i) v[i] = Complex(g(rng), g(rng));
  return v;
}

// Fresh factorization of A with right-hand side b: returns (L, bᴴA⁻¹b).
std::pair<Eigen::SparseMatrix<Complex>, double> fresh(const Eigen::SparseMatrix<Complex>& A,
                                                      const Eigen::VectorXcd& b) {
  UpdatableCholesky F(A);
  F.set_rhs(b);
  return {F.factor(), F.rhs_energy()};
}

void expect_matches_fresh(const UpdatableCholesky& F, const SyntheticCover& cover, const Eigen::VectorXcd& b) {
  const auto A = cover.matrix();
  auto [L, energy] = fresh(A, b);
  const Eigen::SparseMatrix<Complex> diff = F.factor() - L;
  EXPECT_LT(diff.norm(), 1e-9 * L.norm());
  EXPECT_NEAR(F.rhs_energy(), energy, 1e-9 * energy);
  // Independent check of the identity bᴴA⁻¹b = xᴴx through a full solve: A v = b.
  const Eigen::VectorXcd v = F.solve_full();
  EXPECT_LT((A * v - b).norm(), 1e-8 * b.norm());
  EXPECT_NEAR(b.dot(v).real(), energy, 1e-9 * energy);
}

TEST(DengSplit, ReconstructsTheChangeWithEigenvaluesPlusMinusLambda) {
  StarChange c{3, {{7, Complex(0.3, -1.2)}, {1, Complex(-2.0, 0.5)}}};
  auto [w1, w2] = deng_split(c);
  Eigen::MatrixXcd D = Eigen::MatrixXcd::Zero(8, 8), R = Eigen::MatrixXcd::Zero(8, 8);
  for (const auto& e : c.d) D(c.k, e.index) = e.value, D(e.index, c.k) = std::conj(e.value);
  Eigen::VectorXcd v1 = Eigen::VectorXcd::Zero(8), v2 = Eigen::VectorXcd::Zero(8);
  for (const auto& e : w1) v1[e.index] += e.value;
  for (const auto& e : w2) v2[e.index] += e.value;
  R = v1 * v1.adjoint() - v2 * v2.adjoint();
  EXPECT_LT((R - D).norm(), 1e-14 * D.norm());
  const double lambda = std::sqrt(std::norm(c.d[0].value) + std::norm(c.d[1].value));
  EXPECT_LT((D * v1 - lambda * v1).norm(), 1e-13 * lambda);  // w₁ is the eigenvector of +λ
  EXPECT_LT((D * v2 + lambda * v2).norm(), 1e-13 * lambda);  // w₂ of -λ
  EXPECT_NEAR(v1.squaredNorm(), lambda, 1e-13);             // |w_i|² = |λ_i|
}

class OnMeshes : public ::testing::TestWithParam<const char*> {};

// Hundreds of single-edge changes through the path-local trial (each one committed) and a fresh factorization.
TEST_P(OnMeshes, PathLocalUpdatesMatchFreshFactorization) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  std::mt19937 rng(42);
  SyntheticCover cover(mesh, rng);
  UpdatableCholesky F(cover.matrix());
  Eigen::VectorXcd b = random_vector(mesh.num_edges(), rng);
  F.set_rhs(b);
  FactorTrial trial(F.size());
  std::uniform_int_distribution<int> face(0, mesh.num_faces() - 1), slot(0, 2), sign(0, 1);
  for (int it = 0; it < 400; ++it) {
    trial.reset();
    ASSERT_TRUE(trial.add_star_change(F, cover.turn(face(rng), slot(rng), sign(rng) ? 1 : -1))) << "step " << it;
    if (it % 3 == 0) {  // a sparse right-hand side change as well (curl* changes at the edge)
      const SparseEntry db{mesh.FE()(face(rng), slot(rng)), Complex(0.7, -0.2)};
      trial.add_rhs_change(F, std::span(&db, 1));
      b[db.index] += db.value;
    }
    const double predicted = trial.evaluate(F);
    trial.commit(F);
    EXPECT_NEAR(F.rhs_energy(), predicted, 1e-10 * predicted);
    EXPECT_LT(trial.reach(), F.size());
  }
  expect_matches_fresh(F, cover, b);
}

// A trial that is evaluated but not committed leaves the factor untouched, and its value equals the fresh value of
// the changed matrix; multi-edge trials model branch point moves along edge paths (one edge at a time).
TEST_P(OnMeshes, PathMoveTrialsPredictFreshEnergyWithoutChangingTheFactor) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  std::mt19937 rng(7);
  SyntheticCover cover(mesh, rng);
  UpdatableCholesky F(cover.matrix());
  const Eigen::VectorXcd b = random_vector(mesh.num_edges(), rng);
  F.set_rhs(b);
  const Eigen::SparseMatrix<Complex> L0 = F.factor();
  const double e0 = F.rhs_energy();
  FactorTrial trial(F.size());
  for (int it = 0; it < 5; ++it) {
    // A path of edges: walk across faces, turning the edge through which the walk leaves each face.
    const Eigen::MatrixX3i saved = cover.phase;
    trial.reset();
    int f = std::uniform_int_distribution<int>(0, mesh.num_faces() - 1)(rng);
    for (int step = 0; step < 12; ++step) {
      const int a = std::uniform_int_distribution<int>(0, 2)(rng);
      ASSERT_TRUE(trial.add_star_change(F, cover.turn(f, a, 1)));
      if (mesh.neighbor(f, a) >= 0) f = mesh.neighbor(f, a);
    }
    const double predicted = trial.evaluate(F);
    const double expected = fresh(cover.matrix(), b).second;
    EXPECT_NEAR(predicted, expected, 1e-9 * expected);
    cover.phase = saved;  // not committed
  }
  EXPECT_EQ((F.factor() - L0).norm(), 0.0);
  EXPECT_EQ(F.rhs_energy(), e0);
}

// The plain CXSparse route (two cs_ci_updown calls per change, Deng order, full forward solve) agrees too.
TEST_P(OnMeshes, CxsparseUpdownsMatchFreshFactorization) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  std::mt19937 rng(3);
  SyntheticCover cover(mesh, rng);
  UpdatableCholesky F(cover.matrix());
  const Eigen::VectorXcd b = random_vector(mesh.num_edges(), rng);
  F.set_rhs(b);
  std::uniform_int_distribution<int> face(0, mesh.num_faces() - 1), slot(0, 2);
  for (int it = 0; it < 200; ++it) F.apply_star_change_cxsparse(cover.turn(face(rng), slot(rng), it % 2 ? 1 : -1));
  expect_matches_fresh(F, cover, b);
}

// The factor UpdatableCholesky starts from (CHOLMOD supernodal of the matrix permuted by CXSparse's AMD, padding
// pruned) has exactly CXSparse's pattern (column pointers and rows) and its values up to round-off, read from the
// upper triangle alone.
TEST_P(OnMeshes, SupernodalFactorHasTheUpLookingPatternAndValues) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  std::mt19937 rng(11);
  SyntheticCover cover(mesh, rng);
  Eigen::SparseMatrix<Complex> A = cover.matrix();
  A.makeCompressed();
  const int n = static_cast<int>(A.rows());
  cs_ci view{static_cast<int>(A.nonZeros()), n, n, A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(), -1};
  cs_cis* S = cs_ci_schol(1, &view);
  cs_cin* N = cs_ci_chol(&view, S);
  ASSERT_TRUE(S && N);
  Eigen::PermutationMatrix<Eigen::Dynamic> P(n);
  for (int i = 0; i < n; ++i) P.indices()[i] = S->pinv[i];  // P A Pᵀ, full storage: only the upper triangle counts
  Eigen::SparseMatrix<Complex> C(n, n);
  C = A.twistedBy(P);
  C.makeCompressed();
  ColumnFactor cf;
  if (!SparseCholesky<Complex>::cholmod_available()) {
    EXPECT_FALSE(factor_in_given_order(C, cf));
  } else {
    ASSERT_TRUE(factor_in_given_order(C, cf));
    const cs_ci* L = N->L;
    ASSERT_EQ(std::vector<int>(cf.p, cf.p + n + 1), std::vector<int>(L->p, L->p + n + 1));
    ASSERT_EQ(std::vector<int>(cf.i, cf.i + cf.nonzeros()), std::vector<int>(L->i, L->i + L->p[n]));
    double diff = 0, norm = 0;
    for (int q = 0; q < L->p[n]; ++q) diff += std::norm(cf.x[q] - L->x[q]), norm += std::norm(L->x[q]);
    EXPECT_LT(std::sqrt(diff), 1e-12 * std::sqrt(norm));
    // The lower triangle is not read: the upper one alone gives the same numbers.
    Eigen::SparseMatrix<Complex> upper = C.triangularView<Eigen::Upper>();
    upper.makeCompressed();
    ColumnFactor from_upper;
    ASSERT_TRUE(factor_in_given_order(upper, from_upper));
    ASSERT_EQ(from_upper.nonzeros(), cf.nonzeros());
    EXPECT_TRUE(std::equal(cf.x, cf.x + cf.nonzeros(), from_upper.x));
  }
  cs_ci_nfree(N);
  cs_ci_sfree(S);
}

// The same updates on the supernodal route's factor (CHOLMOD's arrays, updated in place) agree with a fresh one.
TEST_P(OnMeshes, PathLocalUpdatesOnTheSupernodalFactorMatchFreshFactorization) {
  const Mesh mesh = testing::load_test_mesh(GetParam());
  std::mt19937 rng(5);
  SyntheticCover cover(mesh, rng);
  UpdatableCholesky F(cover.matrix(), UpdatableCholesky::Route::Supernodal);
  EXPECT_EQ(F.supernodal(), SparseCholesky<Complex>::cholmod_available());
  EXPECT_FALSE(UpdatableCholesky(cover.matrix(), UpdatableCholesky::Route::UpLooking).supernodal());
  Eigen::VectorXcd b = random_vector(mesh.num_edges(), rng);
  F.set_rhs(b);
  FactorTrial trial(F.size());
  std::uniform_int_distribution<int> face(0, mesh.num_faces() - 1), slot(0, 2), sign(0, 1);
  for (int it = 0; it < 200; ++it) {
    trial.reset();
    ASSERT_TRUE(trial.add_star_change(F, cover.turn(face(rng), slot(rng), sign(rng) ? 1 : -1))) << "step " << it;
    const double predicted = trial.evaluate(F);
    trial.commit(F);
    EXPECT_NEAR(F.rhs_energy(), predicted, 1e-10 * predicted);
  }
  for (int it = 0; it < 50; ++it) F.apply_star_change_cxsparse(cover.turn(face(rng), slot(rng), it % 2 ? 1 : -1));
  expect_matches_fresh(F, cover, b);
}

INSTANTIATE_TEST_SUITE_P(Meshes, OnMeshes, ::testing::Values("bunny_3k", "torus_5k", "eight_genus2", "lilium_disk"));

// Mean over the columns j of Σ nnz(L_i) over the etree path from j to the root: the work of an update starting at j.
double mean_path_work(const std::vector<int>& parent, const std::vector<int>& column_count) {
  const int n = static_cast<int>(parent.size());
  std::vector<double> to_root(static_cast<std::size_t>(n));
  double sum = 0;
  for (int j = n - 1; j >= 0; --j) {  // parents come after their children
    to_root[j] = column_count[j] + (parent[j] >= 0 ? to_root[parent[j]] : 0.0);
    sum += to_root[j];
  }
  return sum / n;
}

// The ordering the updates use (nested dissection where CHOLMOD is compiled in) against CXSparse's AMD on the same
// matrix: the paths the updates walk are shorter, and the factor is still exact (the tests above run on it too).
TEST(UpdatableCholesky, NestedDissectionShortensTheUpdatePaths) {
  if (!SparseCholesky<double>::cholmod_available()) GTEST_SKIP() << "the build without CHOLMOD orders by AMD";
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  std::mt19937 rng(3);
  const Eigen::SparseMatrix<Complex> A = SyntheticCover(mesh, rng).matrix();
  const std::vector<int> perm = nested_dissection_ordering(A, 1000);
  ASSERT_EQ(perm.size(), static_cast<std::size_t>(A.rows()));
  std::vector<int> sorted = perm;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < A.rows(); ++i) ASSERT_EQ(sorted[i], i);
  EXPECT_TRUE(nested_dissection_ordering(A, static_cast<int>(A.rows()) + 1).empty());  // below the size limit
  const UpdatableCholesky F(A);
  EXPECT_EQ(F.perm(), perm);
  std::vector<int> counts(static_cast<std::size_t>(F.size()));
  for (int j = 0; j < F.size(); ++j) counts[j] = F.col_ptr()[j + 1] - F.col_ptr()[j];
  const double nested = mean_path_work(F.etree(), counts);
  Eigen::SparseMatrix<Complex> B = A;
  B.makeCompressed();
  cs_ci view{static_cast<int>(B.nonZeros()),
             static_cast<int>(B.rows()),
             static_cast<int>(B.cols()),
             B.outerIndexPtr(),
             B.innerIndexPtr(),
             B.valuePtr(),
             -1};
  cs_cis* S = cs_ci_schol(1, &view);  // AMD
  ASSERT_NE(S, nullptr);
  std::vector<int> amd_parent(S->parent, S->parent + F.size()), amd_counts(static_cast<std::size_t>(F.size()));
  for (int j = 0; j < F.size(); ++j) amd_counts[j] = static_cast<int>(S->cp[j + 1] - S->cp[j]);
  cs_ci_sfree(S);
  EXPECT_LT(nested, 0.8 * mean_path_work(amd_parent, amd_counts));
}

// On a factor of more than kSplitSubstitutionMinColumns columns the full forward solve of a trial runs on two cores
// (the substitution split): its energy for a new right-hand side everywhere is still the fresh factorization's.
TEST(FactorTrial, FullEvaluationOnTwoCoresIsTheFreshEnergy) {
  const Mesh mesh = testing::load_test_mesh("bunny_20k_holes");
  std::mt19937 rng(5);
  SyntheticCover cover(mesh, rng);
  UpdatableCholesky F(cover.matrix());
  ASSERT_GE(F.size(), kSplitSubstitutionMinColumns);
  ASSERT_FALSE(F.substitution_split().empty());
  F.set_rhs(random_vector(mesh.num_edges(), rng));
  FactorTrial trial(F.size());
  int f = 1234;
  for (int step = 0; step < 8; ++step) {
    ASSERT_TRUE(trial.add_star_change(F, cover.turn(f, step % 3, 1)));
    if (mesh.neighbor(f, step % 3) >= 0) f = mesh.neighbor(f, step % 3);
  }
  const Eigen::VectorXcd b_new = random_vector(mesh.num_edges(), rng);
  const double expected = fresh(cover.matrix(), b_new).second;
  EXPECT_NEAR(trial.evaluate_full(F, b_new), expected, 1e-9 * expected);
  trial.commit(F);
  EXPECT_NEAR(F.rhs_energy(), expected, 1e-9 * expected);
}

// A change that makes the matrix indefinite must be detected, not silently produce NaNs.
TEST(FactorTrial, DetectsLossOfPositiveDefiniteness) {
  const Mesh mesh = testing::make_grid(6);
  std::mt19937 rng(1);
  SyntheticCover cover(mesh, rng, 1e-3);
  UpdatableCholesky F(cover.matrix());
  F.set_rhs(Eigen::VectorXcd::Ones(F.size()));
  FactorTrial trial(F.size());
  const int k = mesh.FE()(10, 0), l = mesh.FE()(10, 1);
  // |D(k,l)| far larger than sqrt(A_kk A_ll) makes A + D indefinite.
  const double big = 100 * std::sqrt(cover.matrix().coeff(k, k).real() * cover.matrix().coeff(l, l).real());
  EXPECT_FALSE(trial.add_star_change(F, StarChange{k, {{l, Complex(big, 0)}}}));
  EXPECT_THROW(trial.evaluate(F), NumericalError);
  trial.reset();
  EXPECT_TRUE(trial.add_star_change(F, cover.turn(10, 0, 1)));
}

}  // namespace
}  // namespace quadcover
