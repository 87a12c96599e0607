#pragma once
// Sparse Cholesky factorization computed once and reused for many right-hand sides (thesis 1.2.4). Backed by
// CHOLMOD (supernodal LLᴴ, real or complex Hermitian) when QUADCOVER_HAVE_CHOLMOD, else Eigen's SimplicialLLT
// with AMD ordering. Positive semi-definite stiffness matrices are made definite by the caller (see hodge.h),
// never silently here: no diagonal shift is ever added.
#include <Eigen/SparseCore>
#include <memory>
#include <span>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover {

/// How many OpenMP regions (of CHOLMOD's) this process ran in place, through quadcover's GOMP_parallel instead of
/// libgomp's (sparse_cholesky.cpp); stays 0 where libgomp's is bound first (e.g. a host program linked with
/// libgomp loads the Python module) or without CHOLMOD. \pre none
long long openmp_regions_run_in_place();

/// Which factorization library to use. Automatic = CHOLMOD when compiled in, else Eigen.
enum class CholeskyBackend { Automatic, Cholmod, Eigen };

template <class Scalar>
class SparseCholesky {
 public:
  using Matrix = Eigen::SparseMatrix<Scalar>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Dense = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  SparseCholesky();  ///< CholeskyBackend::Automatic
  /// \throw NumericalError if `backend` is Cholmod and quadcover was built without CHOLMOD.
  explicit SparseCholesky(CholeskyBackend backend);
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  /// True iff quadcover was built with CHOLMOD (QUADCOVER_USE_CHOLMOD=ON). \pre none
  static bool cholmod_available();
  /// The backend in use: Cholmod or Eigen (never Automatic). \pre none
  CholeskyBackend backend() const;

  /// Symbolic analysis + numeric factorization of the symmetric/Hermitian positive definite A (full storage;
  /// only the lower triangle is read). A may be 0 by 0. `ordering` (perm[new] = old), when not empty, is the
  /// fill-reducing order the CHOLMOD backend uses instead of choosing one (AMD, then METIS where AMD fills much);
  /// the Eigen backend always uses its AMD. CHOLMOD's choice for a pattern of 10⁴ rows or more is kept for the
  /// process (the last few patterns): the same factor, without ordering the pattern again.
  /// \throw NumericalError naming `stage` if A is not positive definite (or not square), or if `ordering` is not
  /// empty and not a permutation of A's rows.
  void compute(const Matrix& A, const char* stage = "cholesky", std::span<const int> ordering = {});
  /// Numeric refactorization reusing the symbolic analysis of compute(); A must have the same sparsity pattern.
  /// \throw NumericalError if A is not positive definite, has another pattern, or compute() was never called.
  void refactorize(const Matrix& A);
  /// compute() the first time, refactorize() on later calls while A keeps the analyzed pattern (a fresh analysis
  /// when the number of stored entries changes): for sequences of matrices with one pattern and new values.
  /// `ordering` as in compute(), used when it analyses. \throw NumericalError as compute().
  void factorize(const Matrix& A, const char* stage = "cholesky", std::span<const int> ordering = {});
  /// x with A x = b.  b: rows() entries.
  /// \throw NumericalError if nothing was factored, b has the wrong size, or CHOLMOD fails.
  Vector solve(const Vector& b) const;
  /// X with A X = B, all columns at once.  B: rows() by k. The solves (and forward_solve) only read the factor:
  /// several threads may solve with one factorization at once.
  /// \throw NumericalError if nothing was factored, B has the wrong rows, or CHOLMOD fails.
  Dense solve(const Dense& B) const;
  /// y = L⁻¹ P b for the factorization Pᵀ L Lᴴ P = A, so that bᴴ A⁻¹ b = ‖y‖² (forward substitution only; the
  /// energy E_D of thesis 6.2.1 is ½‖y‖²). \throw NumericalError if nothing was factored or b has the wrong size.
  Vector forward_solve(const Vector& b) const;
  /// Lets solve_sparse() walk the factor column by column, read in place (CHOLMOD's supernodal blocks, Eigen's
  /// compressed columns; no copy): pointers per column and the split of the substitutions. Needed again after
  /// every factorization; once since, it returns at once. \throw NumericalError if nothing was factored.
  void prepare_sparse_solves();
  /// x with A x = r for an r that is zero but at `rows` (r[rows[k]] += values[k]): the forward substitution skips
  /// the columns where it is still zero, so it visits only the elimination-tree paths from those rows; the back
  /// substitution visits every column. Equal to solve(r) up to round-off.
  /// \throw NumericalError if prepare_sparse_solves() was not called after the last factorization, the spans
  /// differ in length or a row is out of range.
  Vector solve_sparse(std::span<const int> rows, std::span<const Scalar> values) const;
  Eigen::Index rows() const;  ///< 0 before compute(). \pre none

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A lower triangular factor in compressed columns: column j holds rows i[p[j]] .. i[p[j+1]-1], increasing, the
/// diagonal first (CXSparse's layout).
struct ColumnFactor {
  int n = 0;
  int* p = nullptr;  ///< n + 1 column pointers
  int* i = nullptr;  ///< p[n] row indices
  Complex* x = nullptr;  ///< p[n] values
  std::shared_ptr<void> storage;  ///< owns the arrays (CHOLMOD's own, no copy)
  long nonzeros() const { return p ? p[n] : 0; }  ///< \pre none
};

/// The Cholesky factor L of C = L Lᴴ in C's own order (C is already P A Pᵀ for a fill-reducing permutation P), with
/// the exact symbolic pattern of C (no supernodal padding): CHOLMOD's supernodal factorization (BLAS-3) converted to
/// simplicial form. C is Hermitian positive definite; only its upper triangle is read (upper or full storage).
/// \return false if quadcover was built without CHOLMOD or C is not positive definite (`out` is then empty).
/// \pre C is square and compressed (else false). Does not throw.
bool factor_in_given_order(const Eigen::SparseMatrix<Complex>& C, ColumnFactor& out);

/// A nested-dissection fill-reducing ordering of A's pattern (perm[new] = old): METIS through CHOLMOD. Its factor
/// has about as many entries as AMD's on meshes, but its elimination tree is lower and bushier, so the paths that
/// path-local Cholesky updates walk (optimize/updatable_cholesky.h) hold 1.3-2.4× fewer entries of L
/// (BENCHMARKS.md, "Nested dissection for the E_D updates").
/// \return the permutation, or empty when quadcover was built without CHOLMOD, A has fewer than `min_size` rows or
/// the ordering fails. \pre A is square with a symmetric pattern (full storage). Deterministic (METIS's fixed seed).
/// The orderings of the last few patterns are kept: a job that solves on one mesh again and again (cone merges,
/// remakes) orders its pattern once.
std::vector<int> nested_dissection_ordering(const Eigen::SparseMatrix<Complex>& A, int min_size);

extern template class SparseCholesky<double>;
extern template class SparseCholesky<Complex>;

}  // namespace quadcover
