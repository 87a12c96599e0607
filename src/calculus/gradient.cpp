// Gradients of conforming and nonconforming PL functions as complex per-face vectors (thesis 1.2).
#include "calculus/gradient.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace quadcover {

namespace {
using CTriplet = Eigen::Triplet<Complex>;
const Complex kJ{0.0, 1.0};  // J: 90° rotation in the face basis

void check_size(Eigen::Index got, int expected, const char* fn, const char* what) {
  if (got != expected)
    throw std::invalid_argument(std::string(fn) + ": " + std::to_string(got) + " values for " +
                                std::to_string(expected) + " " + what);
}
}  // namespace

Eigen::SparseMatrix<Complex> conforming_gradient(const Mesh& mesh) {
  const int nf = mesh.num_faces();
  std::vector<CTriplet> t;
  t.reserve(3 * static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    const double inv2A = 0.5 / mesh.face_areas()[f];
    for (int k = 0; k < 3; ++k)  // ∇φ_p|t = (1/2A_t) J e, e the ccw edge opposite p
      t.emplace_back(f, mesh.F()(f, k), inv2A * kJ * mesh.edge_vector_local(f, k));
  }
  Eigen::SparseMatrix<Complex> G(nf, mesh.num_vertices());
  G.setFromTriplets(t.begin(), t.end());
  return G;
}

Eigen::SparseMatrix<Complex> nonconforming_gradient(const Mesh& mesh) {
  const int nf = mesh.num_faces();
  std::vector<CTriplet> t;
  t.reserve(3 * static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    const double invA = 1.0 / mesh.face_areas()[f];
    for (int k = 0; k < 3; ++k)  // ∇ψ_e|t = -(1/A_t) J e, e ccw in t
      t.emplace_back(f, mesh.FE()(f, k), -invA * kJ * mesh.edge_vector_local(f, k));
  }
  Eigen::SparseMatrix<Complex> G(nf, mesh.num_edges());
  G.setFromTriplets(t.begin(), t.end());
  return G;
}

VectorField gradient(const Mesh& mesh, const Eigen::VectorXd& u) {
  check_size(u.size(), mesh.num_vertices(), "gradient", "vertices");
  VectorField X(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    Complex g = 0;
    for (int k = 0; k < 3; ++k) g += u[mesh.F()(f, k)] * mesh.edge_vector_local(f, k);
    X[f] = kJ * g * (0.5 / mesh.face_areas()[f]);
  }
  return X;
}

VectorField nonconforming_gradient(const Mesh& mesh, const Eigen::VectorXd& v) {
  check_size(v.size(), mesh.num_edges(), "nonconforming_gradient", "edges");
  VectorField X(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    Complex g = 0;
    for (int k = 0; k < 3; ++k) g += v[mesh.FE()(f, k)] * mesh.edge_vector_local(f, k);
    X[f] = -kJ * g / mesh.face_areas()[f];
  }
  return X;
}

}  // namespace quadcover
