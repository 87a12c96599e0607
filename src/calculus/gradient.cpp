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

namespace {

// The per-face gradient matrix of PL functions with one value per entry of `index` (F: vertices, FE: edges):
// ∇|t = (scale / A_t) J Σ_k value(index(t,k)) e_k, e_k the ccw edge vectors of t.
Eigen::SparseMatrix<Complex> face_gradient_matrix(const Mesh& mesh, const Eigen::MatrixX3i& index, int columns,
                                                  double scale) {
  const int nf = mesh.num_faces();
  std::vector<CTriplet> t;
  t.reserve(3 * static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    const double c = scale / mesh.face_areas()[f];
    for (int k = 0; k < 3; ++k) t.emplace_back(f, index(f, k), c * kJ * mesh.edge_vector_local(f, k));
  }
  Eigen::SparseMatrix<Complex> G(nf, columns);
  G.setFromTriplets(t.begin(), t.end());
  return G;
}

// Σ_k value(index(t,k)) e_k on face f.
Complex edge_sum(const Mesh& mesh, const Eigen::MatrixX3i& index, const Eigen::VectorXd& value, int f) {
  Complex g = 0;
  for (int k = 0; k < 3; ++k) g += value[index(f, k)] * mesh.edge_vector_local(f, k);
  return g;
}

}  // namespace

// ∇φ_p|t = (1/2A_t) J e, e the ccw edge opposite p.
Eigen::SparseMatrix<Complex> conforming_gradient(const Mesh& mesh) {
  return face_gradient_matrix(mesh, mesh.F(), mesh.num_vertices(), 0.5);
}

// ∇ψ_e|t = -(1/A_t) J e, e ccw in t.
Eigen::SparseMatrix<Complex> nonconforming_gradient(const Mesh& mesh) {
  return face_gradient_matrix(mesh, mesh.FE(), mesh.num_edges(), -1.0);
}

VectorField gradient(const Mesh& mesh, const Eigen::VectorXd& u) {
  check_size(u.size(), mesh.num_vertices(), "gradient", "vertices");
  VectorField X(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) X[f] = kJ * edge_sum(mesh, mesh.F(), u, f) * (0.5 / mesh.face_areas()[f]);
  return X;
}

VectorField nonconforming_gradient(const Mesh& mesh, const Eigen::VectorXd& v) {
  check_size(v.size(), mesh.num_edges(), "nonconforming_gradient", "edges");
  VectorField X(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) X[f] = -kJ * edge_sum(mesh, mesh.FE(), v, f) / mesh.face_areas()[f];
  return X;
}

}  // namespace quadcover
