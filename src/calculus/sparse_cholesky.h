#pragma once
// Sparse Cholesky factorization computed once and reused for many right-hand sides. Backed by CHOLMOD
// (supernodal, real or complex Hermitian) when QUADCOVER_HAVE_CHOLMOD, else Eigen's SimplicialLLT.
// Positive semi-definite stiffness matrices are made definite by the caller (see hodge.h), never silently here.
#include <Eigen/SparseCore>
#include <memory>

#include "mesh/mesh.h"

namespace quadcover {

template <class Scalar>
class SparseCholesky {
 public:
  using Matrix = Eigen::SparseMatrix<Scalar>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Dense = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  /// Symbolic analysis + numeric factorization of the symmetric/Hermitian positive definite A (full storage).
  /// \throw NumericalError naming `stage` if A is not positive definite.
  void compute(const Matrix& A, const char* stage = "cholesky");
  /// Numeric refactorization reusing the symbolic analysis (same sparsity pattern).
  void refactorize(const Matrix& A);
  Vector solve(const Vector& b) const;
  Dense solve(const Dense& B) const;
  Eigen::Index rows() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

extern template class SparseCholesky<double>;
extern template class SparseCholesky<Complex>;

}  // namespace quadcover
