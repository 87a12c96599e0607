// SparseCholesky<double> and SparseCholesky<complex> (Hermitian) with every available backend: solutions against
// an independent LU solve, CHOLMOD vs Eigen agreement, refactorization, the forward half, and failure on
// indefinite matrices. The matrices come from a real mesh (bunny_3k).
#include "calculus/sparse_cholesky.h"

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "calculus/stiffness.h"
#include "calculus_test_util.h"
#include "common/errors.h"
#include "support/grid_matrix.h"

namespace quadcover {
namespace {

using testing::cached_mesh;
using testing::random_vector;

std::vector<CholeskyBackend> backends() {
  std::vector<CholeskyBackend> b{CholeskyBackend::Eigen};
  if (SparseCholesky<double>::cholmod_available()) b.push_back(CholeskyBackend::Cholmod);
  return b;
}

// 𝔏 + diag(vertex areas) + shift·I: symmetric positive definite with the pattern of 𝔏.
Eigen::SparseMatrix<double> spd_matrix(const Mesh& mesh, double shift = 0) {
  Eigen::SparseMatrix<double> A = conforming_stiffness(mesh);
  const Eigen::VectorXd a = vertex_areas(mesh);
  for (int p = 0; p < mesh.num_vertices(); ++p) A.coeffRef(p, p) += a[p] + shift;
  return A;
}

// A Hermitian matrix with the pattern of 𝔏: off-diagonal 𝔏_pq·e^{iθ_pq}, θ from the edge's transport, diagonal
// Σ_q |𝔏_pq| + A_p (strictly diagonally dominant, hence positive definite).
Eigen::SparseMatrix<Complex> hpd_matrix(const Mesh& mesh) {
  const Eigen::SparseMatrix<double> L = conforming_stiffness(mesh);
  const Eigen::VectorXd a = vertex_areas(mesh);
  std::vector<Eigen::Triplet<Complex>> t;
  Eigen::VectorXd diag = a;
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int p = mesh.E()(e, 0), q = mesh.E()(e, 1);
    const Complex w = L.coeff(p, q) * std::polar(1.0, 0.5 + std::arg(mesh.edge_transport()[e]));
    t.emplace_back(p, q, w);
    t.emplace_back(q, p, std::conj(w));
    diag[p] += std::abs(w);
    diag[q] += std::abs(w);
  }
  for (int p = 0; p < mesh.num_vertices(); ++p) t.emplace_back(p, p, diag[p]);
  Eigen::SparseMatrix<Complex> H(mesh.num_vertices(), mesh.num_vertices());
  H.setFromTriplets(t.begin(), t.end());
  return H;
}

template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> lu_solve(const Eigen::SparseMatrix<Scalar>& A,
                                                  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& b) {
  Eigen::SparseLU<Eigen::SparseMatrix<Scalar>> lu(A);
  return lu.solve(b);
}

Eigen::VectorXcd complex_rhs(Eigen::Index n) {
  return random_vector(n, 61).cast<Complex>() + Complex(0, 1) * random_vector(n, 62).cast<Complex>();
}

TEST(SparseCholesky, RealSolveMatchesLU) {
  const Mesh& mesh = cached_mesh("bunny_3k");
  const Eigen::SparseMatrix<double> A = spd_matrix(mesh);
  const Eigen::VectorXd b = random_vector(A.rows(), 60), reference = lu_solve(A, b);
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<double> chol(backend);
    EXPECT_EQ(chol.backend(), backend);
    chol.compute(A);
    ASSERT_EQ(chol.rows(), A.rows());
    const Eigen::VectorXd x = chol.solve(b);
    EXPECT_LT((A * x - b).norm(), 1e-12 * b.norm());
    EXPECT_LT((x - reference).norm(), 1e-10 * reference.norm());
  }
}

TEST(SparseCholesky, ComplexHermitianSolveMatchesLU) {
  const Mesh& mesh = cached_mesh("bunny_3k");
  const Eigen::SparseMatrix<Complex> H = hpd_matrix(mesh);
  EXPECT_LT(Eigen::SparseMatrix<Complex>(H - Eigen::SparseMatrix<Complex>(H.adjoint())).norm(), 1e-14 * H.norm());
  const Eigen::VectorXcd b = complex_rhs(H.rows()), reference = lu_solve(H, b);
  ASSERT_GT(reference.imag().norm(), 0.1 * reference.norm());  // a genuinely complex solution
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<Complex> chol(backend);
    chol.compute(H);
    const Eigen::VectorXcd x = chol.solve(b);
    EXPECT_LT((H * x - b).norm(), 1e-12 * b.norm());
    EXPECT_LT((x - reference).norm(), 1e-10 * reference.norm());
  }
}

// Both backends produce the same solution when both are built (the Automatic backend is CHOLMOD then).
TEST(SparseCholesky, BackendsAgree) {
  const Mesh& mesh = cached_mesh("torus_5k");
  const Eigen::SparseMatrix<double> A = spd_matrix(mesh);
  const Eigen::SparseMatrix<Complex> H = hpd_matrix(mesh);
  const Eigen::VectorXd b = random_vector(A.rows(), 63);
  const Eigen::VectorXcd c = complex_rhs(H.rows());
  SparseCholesky<double> automatic;
  EXPECT_EQ(automatic.backend(),
            SparseCholesky<double>::cholmod_available() ? CholeskyBackend::Cholmod : CholeskyBackend::Eigen);
  automatic.compute(A);
  SparseCholesky<Complex> automatic_c;
  automatic_c.compute(H);
  const Eigen::VectorXd x0 = automatic.solve(b);
  const Eigen::VectorXcd y0 = automatic_c.solve(c);
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<double> chol(backend);
    chol.compute(A);
    EXPECT_LT((chol.solve(b) - x0).norm(), 1e-11 * x0.norm());
    SparseCholesky<Complex> cchol(backend);
    cchol.compute(H);
    EXPECT_LT((cchol.solve(c) - y0).norm(), 1e-11 * y0.norm());
  }
}

TEST(SparseCholesky, DenseRightHandSidesSolvedColumnwise) {
  const Mesh& mesh = cached_mesh("bunny_3k");
  const Eigen::SparseMatrix<Complex> H = hpd_matrix(mesh);
  Eigen::MatrixXcd B(H.rows(), 3);
  for (int j = 0; j < 3; ++j) B.col(j) = complex_rhs(H.rows()) * Complex(j + 1.0, -j);
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<Complex> chol(backend);
    chol.compute(H);
    const Eigen::MatrixXcd X = chol.solve(B);
    for (int j = 0; j < 3; ++j) {
      const Eigen::VectorXcd bj = B.col(j);
      EXPECT_LT((X.col(j) - chol.solve(bj)).norm(), 1e-13 * X.col(j).norm());
    }
    EXPECT_LT((H * X - B).norm(), 1e-12 * B.norm());
  }
}

// Solves only read the factor: two threads solving with one factorization at once, over and over, get exactly the
// solutions of one thread alone (the period matrix solves its blocks so, param/period_matrix.h).
TEST(SparseCholesky, ConcurrentSolvesWithOneFactorGiveTheSerialSolutions) {
  const Eigen::SparseMatrix<Complex> H = hpd_matrix(cached_mesh("torus_5k"));
  std::vector<Eigen::MatrixXcd> B;
  for (int k = 0; k < 4; ++k) {
    B.emplace_back(H.rows(), 3);
    for (int j = 0; j < 3; ++j) B.back().col(j) = complex_rhs(H.rows()) * Complex(k + 1.0, j - 1.0);
  }
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<Complex> chol(backend);
    chol.compute(H);
    std::vector<Eigen::MatrixXcd> alone;
    for (const auto& b : B) alone.push_back(chol.solve(b));
    std::vector<int> differ(2, 0);
    const auto cycle = [&](int first, int& count) {
      for (int k = 0; k < 20; ++k) {
        const int i = first + k % 2;
        count += chol.solve(B[i]) != alone[i];
        count += chol.forward_solve(Eigen::VectorXcd(B[i].col(0))).norm() <= 0;
      }
    };
    std::thread t([&] { cycle(0, differ[0]); });
    cycle(2, differ[1]);
    t.join();
    EXPECT_EQ(differ[0], 0);
    EXPECT_EQ(differ[1], 0);
    EXPECT_LT((H * alone[0] - B[0]).norm(), 1e-12 * B[0].norm());
  }
}

// Refactorizing with new values on the same pattern equals a fresh factorization.
TEST(SparseCholesky, RefactorizeReusesAnalysis) {
  const Mesh& mesh = cached_mesh("bunny_3k");
  const Eigen::SparseMatrix<double> A1 = spd_matrix(mesh), A2 = spd_matrix(mesh, 0.05);
  const Eigen::VectorXd b = random_vector(A1.rows(), 64);
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<double> chol(backend);
    chol.compute(A1);
    const Eigen::VectorXd x1 = chol.solve(b);
    chol.refactorize(A2);
    const Eigen::VectorXd x2 = chol.solve(b);
    EXPECT_LT((A2 * x2 - b).norm(), 1e-12 * b.norm());
    EXPECT_GT((x1 - x2).norm(), 1e-3 * x1.norm());  // the new values were used
    Eigen::SparseMatrix<double> other = A2;
    other.coeffRef(0, A2.cols() - 1) = 1e-3;  // a new entry changes the pattern
    other.coeffRef(A2.cols() - 1, 0) = 1e-3;
    EXPECT_THROW(chol.refactorize(other), NumericalError);
    // A failed numeric refactorization (indefinite values, same pattern) leaves no usable factor behind.
    Eigen::SparseMatrix<double> indefinite = A2;
    for (int p = 0; p < indefinite.rows(); ++p) indefinite.coeffRef(p, p) = -1.0;
    EXPECT_THROW(chol.refactorize(indefinite), NumericalError);
    EXPECT_THROW(chol.solve(b), NumericalError);
  }
}

// factorize(): analyses once, refactorizes while the pattern stays, analyses afresh when it changes; always the
// same solution as a fresh factorization.
TEST(SparseCholesky, FactorizeFollowsThePattern) {
  const Mesh& mesh = cached_mesh("bunny_3k");
  const Eigen::SparseMatrix<double> A1 = spd_matrix(mesh), A2 = spd_matrix(mesh, 0.05);
  Eigen::SparseMatrix<double> other = A2;
  other.coeffRef(0, A2.cols() - 1) = 1e-3;
  other.coeffRef(A2.cols() - 1, 0) = 1e-3;
  const Eigen::VectorXd b = random_vector(A1.rows(), 66);
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<double> chol(backend);
    for (const Eigen::SparseMatrix<double>* A : {&A1, &A2, static_cast<const Eigen::SparseMatrix<double>*>(&other), &A1}) {
      chol.factorize(*A, "sequence");
      SparseCholesky<double> fresh(backend);
      fresh.compute(*A);
      EXPECT_LT((chol.solve(b) - fresh.solve(b)).norm(), 1e-10 * fresh.solve(b).norm());
      EXPECT_LT((*A * chol.solve(b) - b).norm(), 1e-12 * b.norm());
    }
  }
}

// bᴴ A⁻¹ b = ‖y‖² for the forward half y = L⁻¹ P b (the E_D evaluation of thesis 6.2.1).
TEST(SparseCholesky, ForwardSolveGivesEnergy) {
  const Mesh& mesh = cached_mesh("bunny_3k");
  const Eigen::SparseMatrix<double> A = spd_matrix(mesh);
  const Eigen::SparseMatrix<Complex> H = hpd_matrix(mesh);
  const Eigen::VectorXd b = random_vector(A.rows(), 65);
  const Eigen::VectorXcd c = complex_rhs(H.rows());
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<double> chol(backend);
    chol.compute(A);
    const double energy = b.dot(chol.solve(b));
    EXPECT_NEAR(chol.forward_solve(b).squaredNorm(), energy, 1e-10 * energy);
    SparseCholesky<Complex> cchol(backend);
    cchol.compute(H);
    const Complex cenergy = c.dot(cchol.solve(c));  // cᴴ H⁻¹ c, real and positive
    EXPECT_LT(std::abs(cenergy.imag()), 1e-10 * cenergy.real());
    EXPECT_NEAR(cchol.forward_solve(c).squaredNorm(), cenergy.real(), 1e-10 * cenergy.real());
  }
}

// A right-hand side of a few entries (one repeated) solved through the columns of the factor equals the full solve,
// real and complex, on both backends; the full solve still works on the converted factor.
template <class Scalar>
void expect_sparse_solve_is_the_full_one(const Eigen::SparseMatrix<Scalar>& A) {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const std::vector<int> rows{17, 400, 17, static_cast<int>(A.rows()) - 1, 1203};
  const std::vector<Scalar> values{Scalar(0.5), Scalar(-2.0), Scalar(1.25), Scalar(3.0), Scalar(0.75)};
  Vector r = Vector::Zero(A.rows());
  for (std::size_t k = 0; k < rows.size(); ++k) r[rows[k]] += values[k];
  for (const CholeskyBackend backend : backends()) {
    SCOPED_TRACE(backend == CholeskyBackend::Eigen ? "Eigen" : "CHOLMOD");
    SparseCholesky<Scalar> chol(backend);
    chol.compute(A);
    const Vector full = chol.solve(r);
    chol.prepare_sparse_solves();
    const Vector sparse = chol.solve_sparse(rows, values);
    EXPECT_LT((sparse - full).norm(), 1e-12 * full.norm());
    EXPECT_LT((A * sparse - r).norm(), 1e-12 * r.norm());
    EXPECT_LT((chol.solve(r) - full).norm(), 1e-12 * full.norm());
    const Vector single =
        chol.solve_sparse(std::span<const int>(rows.data(), 1), std::span<const Scalar>(values.data(), 1));
    Vector e = Vector::Zero(A.rows());
    e[rows[0]] = values[0];
    EXPECT_LT((A * single - e).norm(), 1e-12 * std::abs(values[0]));
  }
}

TEST(SparseCholesky, SparseRightHandSideSolvesAsTheFullSolve) {
  const Mesh& mesh = cached_mesh("bunny_3k");
  expect_sparse_solve_is_the_full_one(spd_matrix(mesh));
  expect_sparse_solve_is_the_full_one(hpd_matrix(mesh));
}

// solve_sparse() needs prepare_sparse_solves() after each factorization, one value per row and rows in range.
TEST(SparseCholesky, SparseSolveChecksItsPreparationAndInput) {
  const Eigen::SparseMatrix<double> A = spd_matrix(cached_mesh("bunny_3k"));
  const std::vector<int> rows{3};
  const std::vector<double> values{1.0};
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<double> chol(backend);
    EXPECT_THROW(chol.prepare_sparse_solves(), NumericalError);
    chol.compute(A);
    EXPECT_THROW(chol.solve_sparse(rows, values), NumericalError);
    chol.prepare_sparse_solves();
    EXPECT_NO_THROW(chol.solve_sparse(rows, values));
    EXPECT_THROW(chol.solve_sparse(rows, std::vector<double>{}), NumericalError);
    EXPECT_THROW(chol.solve_sparse(std::vector<int>{static_cast<int>(A.rows())}, values), NumericalError);
    EXPECT_THROW(chol.solve_sparse(std::vector<int>{-1}, values), NumericalError);
    chol.refactorize(A);
    EXPECT_THROW(chol.solve_sparse(rows, values), NumericalError);
    chol.prepare_sparse_solves();  // a refactorization of the simplicial factor, converted again
    const Eigen::VectorXd x = chol.solve_sparse(rows, values);
    EXPECT_NEAR((A * x)[3], 1.0, 1e-12);
  }
}

// An indefinite matrix (𝔏 - δI has the negative eigenvalue -δ) raises NumericalError naming the stage.
TEST(SparseCholesky, IndefiniteMatrixThrows) {
  const Mesh& mesh = cached_mesh("bunny_3k");
  Eigen::SparseMatrix<double> A = conforming_stiffness(mesh);
  for (int p = 0; p < A.rows(); ++p) A.coeffRef(p, p) -= 1e-3;
  const Eigen::SparseMatrix<Complex> H = -hpd_matrix(mesh);
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<double> chol(backend);
    try {
      chol.compute(A, "test stage");
      ADD_FAILURE() << "no exception";
    } catch (const NumericalError& e) {
      EXPECT_EQ(e.stage(), "test stage");
    }
    SparseCholesky<Complex> cchol(backend);
    EXPECT_THROW(cchol.compute(H), NumericalError);
    EXPECT_THROW(cchol.solve(Eigen::VectorXcd(Eigen::VectorXcd::Ones(3))), NumericalError);  // nothing was factorized
  }
}

// Debian's CHOLMOD opens OpenMP regions of a fixed 4 threads in each supernodal factorization; on 2 cores beside the
// TBB threads they cost a quarter of a job in waiting. The thread that factors (here not the one that made the
// object) runs them alone afterwards: OpenMP's max-active-levels is 0 there (looked up at run time, as the library
// does; it needs a CHOLMOD built with OpenMP, as Debian's is).
TEST(SparseCholesky, CholmodRunsItsOpenMpRegionsOnTheCallingThread) {
  if (!SparseCholesky<double>::cholmod_available()) GTEST_SKIP() << "the build without CHOLMOD (05_no_cholmod.sh)";
  using Get = int (*)();
  const auto max_active_levels = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
  ASSERT_NE(max_active_levels, nullptr) << "CHOLMOD is not linked with OpenMP";
  const Eigen::SparseMatrix<double> A = spd_matrix(cached_mesh("bunny_3k"));
  SparseCholesky<double> chol(CholeskyBackend::Cholmod);
  int before = -1, after = -1;
  std::thread([&] {
    before = max_active_levels();
    chol.compute(A);
    after = max_active_levels();
  }).join();
  EXPECT_GT(before, 0);
  EXPECT_EQ(after, 0);
  // and without libgomp's team set-up: its regions come through quadcover's GOMP_parallel
  const long long in_place = openmp_regions_run_in_place();
  chol.compute(A);
  EXPECT_GT(openmp_regions_run_in_place(), in_place);
  const Eigen::VectorXd b = random_vector(A.rows(), 63);
  EXPECT_LT((A * chol.solve(b) - b).norm(), 1e-12 * b.norm());
}

// A with one more pair of entries (0, k), (k, 0): another pattern of the same size.
Eigen::SparseMatrix<Complex> with_entry_to(const Eigen::SparseMatrix<Complex>& A, int k) {
  Eigen::SparseMatrix<Complex> B = A;
  B.coeffRef(0, k) += Complex(1e-3, 0);
  B.coeffRef(k, 0) += Complex(1e-3, 0);
  B.makeCompressed();
  return B;
}

// METIS keeps its random state in globals: orderings computed on two threads at once (batch jobs, the parallel
// set-up of Algorithm 6.1) must still be the ones a single thread computes, or the outputs depend on timing. Each
// thread cycles through four patterns, eight in all: more than the orderings kept, so every call orders anew.
TEST(SparseCholesky, NestedDissectionIsTheSameOnConcurrentThreads) {
  if (!SparseCholesky<double>::cholmod_available()) GTEST_SKIP() << "the build without CHOLMOD orders by AMD";
  std::vector<Eigen::SparseMatrix<Complex>> mats;
  for (const char* name : {"bunny_3k", "torus_5k"}) {
    const Eigen::SparseMatrix<Complex> A = hpd_matrix(cached_mesh(name));
    for (int k : {0, 1, 2, 3}) mats.push_back(with_entry_to(A, static_cast<int>(A.rows()) / (k + 2)));
  }
  std::vector<std::vector<int>> alone;
  for (const auto& A : mats) alone.push_back(nested_dissection_ordering(A, 1));
  ASSERT_EQ(alone[0].size(), static_cast<std::size_t>(mats[0].rows()));
  ASSERT_NE(alone[0], alone[1]);  // the patterns differ, and so do their orderings
  std::vector<int> differ(2, 0);
  const auto cycle = [&](int first, int& count) {
    for (int k = 0; k < 20; ++k) count += nested_dissection_ordering(mats[first + k % 4], 1) != alone[first + k % 4];
  };
  std::thread t([&] { cycle(0, differ[0]); });
  cycle(4, differ[1]);
  t.join();
  EXPECT_EQ(differ[0], 0);
  EXPECT_EQ(differ[1], 0);
}

// A job orders one pattern again and again (each remake of the map on the same mesh): the ordering of a pattern
// seen before is the one computed then, whatever the values.
TEST(SparseCholesky, NestedDissectionOfAKnownPatternIsTheKeptOne) {
  if (!SparseCholesky<double>::cholmod_available()) GTEST_SKIP() << "the build without CHOLMOD orders by AMD";
  const Eigen::SparseMatrix<Complex> A = hpd_matrix(cached_mesh("bunny_3k"));
  const std::vector<int> first = nested_dissection_ordering(A, 1);
  const Eigen::SparseMatrix<Complex> scaled = Complex(0, 2) * A;
  EXPECT_EQ(nested_dissection_ordering(scaled, 1), first);
  const std::vector<int> other = nested_dissection_ordering(with_entry_to(A, 7), 1);
  EXPECT_TRUE(std::is_permutation(other.begin(), other.end(), first.begin()));
  EXPECT_TRUE(nested_dissection_ordering(A, static_cast<int>(A.rows()) + 1).empty());  // below min_size
}

// CHOLMOD's ordering of a large pattern is kept and used for the next matrix of that pattern: the factor is the
// same bit for bit as the first one (the ordering is not chosen anew, but the choice would be the same).
TEST(SparseCholesky, KeptChoiceOfOrderingGivesTheSameFactor) {
  const Eigen::SparseMatrix<double> A =
      testing::grid_matrix<double>(120);  // 14400 rows: above the size whose orderings are kept
  const Eigen::VectorXd b = random_vector(A.rows(), 64);
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<double> first(backend), second(backend);
    first.compute(A);
    second.compute(A);
    EXPECT_EQ(second.forward_solve(b), first.forward_solve(b)) << "not the same ordering";
    EXPECT_LT((A * second.solve(b) - b).norm(), 1e-12 * b.norm());
  }
}

// compute() with a given ordering: the same solution, the factor of that order (another L⁻¹Pb of the same norm),
// and a clear error for a list that is not a permutation.
TEST(SparseCholesky, GivenOrderingIsUsedAndChecked) {
  const Eigen::SparseMatrix<Complex> H = hpd_matrix(cached_mesh("bunny_3k"));
  const int n = static_cast<int>(H.rows());
  const Eigen::VectorXcd b = complex_rhs(n), reference = lu_solve(H, b);
  std::vector<int> reversed(n);
  for (int k = 0; k < n; ++k) reversed[k] = n - 1 - k;
  for (const CholeskyBackend backend : backends()) {
    SparseCholesky<Complex> chosen(backend), given(backend);
    chosen.compute(H);
    given.compute(H, "given", reversed);
    EXPECT_LT((given.solve(b) - reference).norm(), 1e-10 * reference.norm());
    const Eigen::VectorXcd y_chosen = chosen.forward_solve(b), y_given = given.forward_solve(b);
    EXPECT_NEAR(y_given.squaredNorm(), y_chosen.squaredNorm(), 1e-10 * y_chosen.squaredNorm());
    if (backend == CholeskyBackend::Cholmod) {
      EXPECT_GT((y_given - y_chosen).norm(), 1e-3 * y_chosen.norm());
    }
    std::vector<int> twice = reversed;
    twice[1] = twice[0];
    try {
      given.compute(H, "given", twice);
      ADD_FAILURE() << "a repeated index was accepted";
    } catch (const NumericalError& e) {
      EXPECT_NE(std::string(e.what()).find("not a permutation"), std::string::npos) << e.what();
    }
    EXPECT_THROW(given.compute(H, "given", std::span<const int>(reversed).first(n - 1)), NumericalError);
  }
}

TEST(SparseCholesky, EmptyMatrixAndBackendAvailability) {
  SparseCholesky<double> chol;
  chol.compute(Eigen::SparseMatrix<double>(0, 0));
  EXPECT_EQ(chol.rows(), 0);
  EXPECT_EQ(chol.solve(Eigen::VectorXd(0)).size(), 0);
  if (SparseCholesky<double>::cholmod_available())
    EXPECT_EQ(SparseCholesky<Complex>(CholeskyBackend::Cholmod).backend(), CholeskyBackend::Cholmod);
  else
    EXPECT_THROW(SparseCholesky<Complex>(CholeskyBackend::Cholmod), NumericalError);
}

}  // namespace
}  // namespace quadcover
