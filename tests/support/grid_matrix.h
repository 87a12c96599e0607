#pragma once
// The 5-point Laplacian of a k by k grid plus the identity, shared by the tests that factor or order a large sparse
// matrix of known pattern.
#include <Eigen/SparseCore>
#include <vector>

namespace quadcover::testing {

/// The 5-point Laplacian of a k by k grid plus the identity: Hermitian positive definite, k² rows.
template <class Scalar>
Eigen::SparseMatrix<Scalar> grid_matrix(int k) {
  std::vector<Eigen::Triplet<Scalar>> t;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const int p = i * k + j;
      t.emplace_back(p, p, Scalar(5));
      if (i + 1 < k) t.emplace_back(p, p + k, Scalar(-1)), t.emplace_back(p + k, p, Scalar(-1));
      if (j + 1 < k) t.emplace_back(p, p + 1, Scalar(-1)), t.emplace_back(p + 1, p, Scalar(-1));
    }
  Eigen::SparseMatrix<Scalar> A(k * k, k * k);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace quadcover::testing
