// L² inner product of piecewise constant tangent fields (thesis 1.2).
#include "calculus/vector_field.h"

namespace quadcover {

double l2_inner(const Mesh& mesh, const VectorField& X, const VectorField& Y) {
  double sum = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) sum += mesh.face_areas()[f] * (std::conj(X[f]) * Y[f]).real();
  return sum;
}

double l2_norm_squared(const Mesh& mesh, const VectorField& X) { return l2_inner(mesh, X, X); }

}  // namespace quadcover
