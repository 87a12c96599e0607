// Discrete divergence and curl (Def. 1.11, (1.6)), assembled face by face so that missing triangles at the
// boundary simply contribute nothing.
#include "calculus/div_curl.h"

#include <stdexcept>

namespace quadcover {

namespace {

void check_field(const Mesh& mesh, const VectorField& X, const char* fn) {
  if (X.size() != mesh.num_faces())
    throw std::invalid_argument(std::string(fn) + ": field has " + std::to_string(X.size()) + " entries, mesh has " +
                                std::to_string(mesh.num_faces()) + " faces");
}

double dot(Complex a, Complex b) { return (std::conj(a) * b).real(); }  // Euclidean ⟨a, b⟩ in the face basis
const Complex kJ{0.0, 1.0};

}  // namespace

Eigen::VectorXd divergence(const Mesh& mesh, const VectorField& X) {
  check_field(mesh, X, "divergence");
  Eigen::VectorXd d = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) d[mesh.F()(f, k)] -= 0.5 * dot(X[f], kJ * mesh.edge_vector_local(f, k));  // (1.6)
  return d;
}

Eigen::VectorXd curl(const Mesh& mesh, const VectorField& X) {
  check_field(mesh, X, "curl");
  Eigen::VectorXd c = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) c[mesh.F()(f, k)] += 0.5 * dot(X[f], mesh.edge_vector_local(f, k));  // (1.6)
  return c;
}

// In face f the edge e = FE(f,k) appears as the ccw vector e_f = ±e (+ in s, - in t), so the face's share of
// div* is ⟨X_f, J e_f⟩ and of curl* is -⟨X_f, e_f⟩, whichever side f is on.
Eigen::VectorXd divergence_star(const Mesh& mesh, const VectorField& X) {
  check_field(mesh, X, "divergence_star");
  Eigen::VectorXd d = Eigen::VectorXd::Zero(mesh.num_edges());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) d[mesh.FE()(f, k)] += dot(X[f], kJ * mesh.edge_vector_local(f, k));
  return d;
}

Eigen::VectorXd curl_star(const Mesh& mesh, const VectorField& X) {
  check_field(mesh, X, "curl_star");
  Eigen::VectorXd c = Eigen::VectorXd::Zero(mesh.num_edges());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) c[mesh.FE()(f, k)] -= dot(X[f], mesh.edge_vector_local(f, k));
  return c;
}

}  // namespace quadcover
