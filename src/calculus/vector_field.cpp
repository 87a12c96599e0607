// L² inner product of piecewise constant tangent fields (thesis 1.2).
#include "calculus/vector_field.h"

#include <stdexcept>
#include <string>

namespace quadcover {

double l2_inner(const Mesh& mesh, const VectorField& X, const VectorField& Y) {
  if (X.size() != mesh.num_faces() || Y.size() != mesh.num_faces())
    throw std::invalid_argument("l2_inner: fields have " + std::to_string(X.size()) + " and " +
                                std::to_string(Y.size()) + " entries, mesh has " + std::to_string(mesh.num_faces()) +
                                " faces");
  double sum = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) sum += mesh.face_areas()[f] * (std::conj(X[f]) * Y[f]).real();
  return sum;
}

double l2_norm_squared(const Mesh& mesh, const VectorField& X) { return l2_inner(mesh, X, X); }

}  // namespace quadcover
