#pragma once
// Piecewise constant tangent vector fields 𝔛(M) (thesis 1.2): one complex number per face, the vector's
// coordinates in the face basis (b1, b2) of Mesh. J (90° rotation, thesis 1.2) is multiplication by i.
#include <Eigen/Core>

#include "mesh/mesh.h"

namespace quadcover {

/// #F complex: X_t in face t's basis.
using VectorField = Eigen::VectorXcd;

/// L² inner product ⟨X, Y⟩ = Σ_t A_t ⟨X_t, Y_t⟩ (real part of conj(X_t)·Y_t).
/// \throw std::invalid_argument if X or Y does not have #F entries.
double l2_inner(const Mesh& mesh, const VectorField& X, const VectorField& Y);
/// ‖X‖² = ⟨X, X⟩. \throw std::invalid_argument if X does not have #F entries.
double l2_norm_squared(const Mesh& mesh, const VectorField& X);

}  // namespace quadcover
