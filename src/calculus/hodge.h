#pragma once
// Discrete Hodge decomposition X = X_P + X_C + X_H (Theorem 1.12) via (1.8)-(1.10), factorizing 𝔏 and 𝔏* once
// and reusing the factors for every field. The constant kernel is removed per connected component by the
// normalization ∫u = 0 (1.10).
#include <memory>

#include "calculus/vector_field.h"

namespace quadcover {

struct HodgeParts {
  VectorField exact;     ///< X_P = ∇u, u ∈ S_h
  VectorField coexact;   ///< X_C = J∇v, v ∈ S_h*
  VectorField harmonic;  ///< X_H = X - X_P - X_C
  Eigen::VectorXd potential;    ///< u, #V, ∫u dA = 0 per component
  Eigen::VectorXd copotential;  ///< v, #E, ∫v dA = 0 per component
};

class HodgeDecomposer {
 public:
  /// Factorizes 𝔏 and 𝔏* of the mesh (once). \throw NumericalError if a factorization fails.
  explicit HodgeDecomposer(const Mesh& mesh);
  ~HodgeDecomposer();
  HodgeDecomposer(HodgeDecomposer&&) noexcept;

  HodgeParts decompose(const VectorField& X) const;
  /// u with 𝔏u = -div X (1.8), normalized (1.10).
  Eigen::VectorXd exact_potential(const VectorField& X) const;
  /// v with 𝔏*v = -curl* X (1.9), normalized (1.10).
  Eigen::VectorXd coexact_potential(const VectorField& X) const;
  /// Solves 𝔏u = rhs (rhs summing to zero per component), normalized; and 𝔏*v = rhs likewise.
  Eigen::VectorXd solve_conforming(const Eigen::VectorXd& rhs) const;
  Eigen::VectorXd solve_nonconforming(const Eigen::VectorXd& rhs) const;

  const Mesh& mesh() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace quadcover
