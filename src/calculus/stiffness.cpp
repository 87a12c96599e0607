// Stiffness matrices 𝔏, 𝔏*, the incidence C and the lumped areas (thesis 1.2.1).
#include "calculus/stiffness.h"

#include <vector>

namespace quadcover {

namespace {
using Triplet = Eigen::Triplet<double>;
}

Eigen::SparseMatrix<double> edge_vertex_incidence(const Mesh& mesh) {
  const int ne = mesh.num_edges();
  std::vector<Triplet> t;
  t.reserve(2 * static_cast<std::size_t>(ne));
  for (int e = 0; e < ne; ++e) {
    t.emplace_back(e, mesh.E()(e, 0), 1.0);  // C_pe = 1 iff p ∈ e (stored transposed)
    t.emplace_back(e, mesh.E()(e, 1), 1.0);
  }
  Eigen::SparseMatrix<double> C(ne, mesh.num_vertices());
  C.setFromTriplets(t.begin(), t.end());
  return C;
}

// Both matrices are assembled face by face from the local Gram matrix of the face's edge vectors e_a (counter-
// clockwise): ∫_t ⟨∇ψ_a, ∇ψ_b⟩ = ⟨e_a, e_b⟩ / A_t because ∇ψ_a|t = -(1/A_t) J e_a, and ∇φ_a = -½ ∇ψ_a on t
// (φ_a = ½(1 - ψ_a) there), so the conforming entries are a quarter of that. For a ≠ b, ⟨e_a, e_b⟩ / A_t =
// -2 cot of the angle between them, which is (1.5); the diagonal is minus the row sum since Σ_a e_a = 0.
namespace {

// Σ_t (scale / A_t) ⟨e_a, e_b⟩ at (index(t,a), index(t,b)): the face-by-face assembly of both matrices.
Eigen::SparseMatrix<double> gram_assembly(const Mesh& mesh, const Eigen::MatrixX3i& index, int n, double scale) {
  const int nf = mesh.num_faces();
  std::vector<Triplet> t;
  t.reserve(9 * static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    const double c = scale / mesh.face_areas()[f];
    for (int a = 0; a < 3; ++a) {
      const Complex ea = mesh.edge_vector_local(f, a);
      for (int b = 0; b < 3; ++b)
        t.emplace_back(index(f, a), index(f, b), c * (std::conj(ea) * mesh.edge_vector_local(f, b)).real());
    }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

}  // namespace

Eigen::SparseMatrix<double> conforming_stiffness(const Mesh& mesh) {
  return gram_assembly(mesh, mesh.F(), mesh.num_vertices(), 0.25);
}

Eigen::SparseMatrix<double> nonconforming_stiffness(const Mesh& mesh) {
  return gram_assembly(mesh, mesh.FE(), mesh.num_edges(), 1.0);  // (1.5)
}

Eigen::VectorXd vertex_areas(const Mesh& mesh) {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) a[mesh.F()(f, k)] += mesh.face_areas()[f] / 3.0;  // ∫φ_p = Σ A_t / 3
  return a;
}

Eigen::VectorXd edge_areas(const Mesh& mesh) {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(mesh.num_edges());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) a[mesh.FE()(f, k)] += mesh.face_areas()[f] / 3.0;  // ∫ψ_e = (A_s + A_t) / 3
  return a;
}

}  // namespace quadcover
