#include "common/quarter_turn.h"
#include "field/frame_field.h"

#include <cmath>

namespace quadcover {

FrameField make_cross_field(Eigen::VectorXcd X, Eigen::VectorXi matching) {
  FrameField f;
  f.Y = Complex(0, 1) * X;
  f.X = std::move(X);
  f.matching = std::move(matching);
  return f;
}

Eigen::VectorXcd orthogonalized_frames(const FrameField& field) {
  Eigen::VectorXcd Z(field.X.size());
  for (Eigen::Index t = 0; t < Z.size(); ++t) Z[t] = orthogonalized(field.X[t], field.Y[t]);
  return Z;
}

std::pair<Complex, Complex> frame_switch(Complex X, Complex Y, int k) {
  switch (mod4(k)) {
    case 0:
      return {X, Y};
    case 1:
      return {Y, -X};
    case 2:
      return {-X, -Y};
    default:
      return {-Y, X};
  }
}

CrossDirections cross_directions(const Mesh& mesh, const FrameField& field) {
  const int nf = mesh.num_faces();
  CrossDirections d;
  d.u.resize(nf, 3);
  d.v.resize(nf, 3);
  for (int t = 0; t < nf; ++t) {
    Complex z = orthogonalized(field.X[t], field.Y[t]);
    z = std::abs(z) > 0 ? z / std::abs(z) : Complex(1, 0);
    d.u.row(t) = mesh.to_world(t, z).transpose();
    d.v.row(t) = mesh.to_world(t, Complex(0, 1) * z).transpose();
  }
  return d;
}

}  // namespace quadcover
