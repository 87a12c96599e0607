#pragma once
// Seam transitions of a per-corner map (thesis 4.2.2): across each interior edge e (s = EF(e,0), t = EF(e,1)) a
// seamless integer-grid map satisfies φ_t = i^k φ_s + c with k ∈ {0..3} and c ∈ Z[i]. Files such as a
// parameterized OBJ carry only per-corner coordinates; these functions recover (k, c) from the corner values.
#include <Eigen/Core>

#include "mesh/mesh.h"
#include "param/parameterization.h"

namespace quadcover {

struct TransitionFit {
  Eigen::VectorXi rotation;      ///< #E: k ∈ 0..3, 0 on boundary edges
  Eigen::VectorXcd translation;  ///< #E: c as fitted (not rounded), 0 on boundary edges
  /// #E: max over the two edge endpoints of |φ_t - (i^k φ_s + c)| for the best k; 0 on boundary edges.
  Eigen::VectorXd residual;
  /// #E: distance of c to the nearest Gaussian integer (the seamlessness defect of an integer-grid map).
  Eigen::VectorXd integer_defect;
};

/// Fits the rotation k minimizing the residual, then c from the edge midpoint. uv is #F by 3 (per corner φ).
/// \pre uv.rows() == #F. \throw only std::bad_alloc.
TransitionFit fit_transitions(const Mesh& mesh, const Eigen::MatrixX3cd& uv);

/// A Parameterization from per-corner coordinates: fitted transitions with translations rounded to Z[i], cut
/// edges where the transition is not the identity. Branch points and energies are left empty (unknown).
/// \pre uv.rows() == #F. \throw only std::bad_alloc.
Parameterization parameterization_from_uv(const Mesh& mesh, const Eigen::MatrixX3cd& uv);

}  // namespace quadcover
