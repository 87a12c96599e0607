#pragma once
// Discrete divergence and curl of piecewise constant fields (Def. 1.11, formulas (1.6)); at boundary vertices and
// edges the terms of missing triangles vanish. Averaging property (1.7): div = ½ Cᵀ div*, curl = ½ Cᵀ curl*.
#include <Eigen/Core>

#include "calculus/vector_field.h"

namespace quadcover {

Eigen::VectorXd divergence(const Mesh& mesh, const VectorField& X);       ///< div X, #V
Eigen::VectorXd curl(const Mesh& mesh, const VectorField& X);             ///< curl X, #V
Eigen::VectorXd divergence_star(const Mesh& mesh, const VectorField& X);  ///< div* X, #E  (1.6)
Eigen::VectorXd curl_star(const Mesh& mesh, const VectorField& X);        ///< curl* X, #E (1.6), s = EF(e,0), t = EF(e,1)

}  // namespace quadcover
