#pragma once
// Discrete divergence and curl of piecewise constant fields (Def. 1.11, formulas (1.6)); at boundary vertices and
// edges the terms of missing triangles vanish. Averaging property (1.7): div = ½ Cᵀ div*, curl = ½ Cᵀ curl*.
//
// Sign of curl*: we follow the integral definition of Def. 1.11 (τ counter-clockwise along ∂star(e)), which is
// what (1.7), curl* = -div* J, the system (1.9) and the frame-field curl (3.3) all use:
//     curl* X(e) = ⟨X_t, e⟩ - ⟨X_s, e⟩,   s = EF(e,0) (e positively oriented in s), t = EF(e,1).
// The explicit formula printed in (1.6), ⟨X_s, e⟩ - ⟨X_t, e⟩, has the opposite sign of its own "= -div* JX".
// div* X(e) = ⟨X_s, Je⟩ - ⟨X_t, Je⟩ as printed. Both are independent of the orientation of e.
// All four throw std::invalid_argument if X does not have #F entries.
//
// Reference implementation on the real surface M (used by calculus/hodge.h): the product works with the covering's
// complex operators (cover/complex_stiffness.h); tests/param/reference_stack_test.cpp checks the two against each
// other through the Hodge decomposition.
#include <Eigen/Core>

#include "calculus/vector_field.h"

namespace quadcover {

/// div X(p) = -½ Σ_{t∋p} ⟨X_t, J e_t⟩ = -∫⟨X, ∇φ_p⟩ (1.6), #V.  X: #F. \throw std::invalid_argument if X.size() != #F.
Eigen::VectorXd divergence(const Mesh& mesh, const VectorField& X);
/// curl X(p) = ½ Σ_{t∋p} ⟨X_t, e_t⟩ = -div JX(p) (1.6), #V. \throw std::invalid_argument if X.size() != #F.
Eigen::VectorXd curl(const Mesh& mesh, const VectorField& X);
/// div* X(e) = ⟨X_s - X_t, J e⟩ = -∫⟨X, ∇ψ_e⟩ (1.6), #E. \throw std::invalid_argument if X.size() != #F.
Eigen::VectorXd divergence_star(const Mesh& mesh, const VectorField& X);
/// curl* X(e) = ⟨X_t - X_s, e⟩ = -div* JX(e), #E (see the sign note above); s = EF(e,0), t = EF(e,1).
/// \throw std::invalid_argument if X.size() != #F.
Eigen::VectorXd curl_star(const Mesh& mesh, const VectorField& X);

}  // namespace quadcover
