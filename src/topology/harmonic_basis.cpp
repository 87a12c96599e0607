#include "topology/harmonic_basis.h"

#include <span>
#include <string>

#include "calculus/gradient.h"
#include "common/errors.h"

namespace quadcover {
namespace {

// Adds ∇φ_p on the faces of the wedge of p left of a visit of γ_k (1.13). The visit arrives from `in` and leaves
// to `out` (-1: the walk starts / ends here, at a boundary vertex). The wedge runs counter-clockwise from the face
// left of p -> out to the face left of in -> p; at a walk end it extends to the end / start of the boundary fan.
void add_visit(const Mesh& mesh, int k, int p, int in, int out, std::vector<Eigen::Triplet<Complex>>& entries) {
  const auto fan = mesh.fan(p);
  const int n = static_cast<int>(fan.size());
  int first = -1, last = -1;
  for (int i = 0; i < n; ++i) {
    const int f = fan[i].face, c = fan[i].corner;
    if (out >= 0 && mesh.F()(f, (c + 1) % 3) == out) first = i;  // face containing p -> out positively
    if (in >= 0 && mesh.F()(f, (c + 2) % 3) == in) last = i;     // face containing in -> p positively
  }
  const bool boundary = mesh.is_boundary_vertex(p);
  if (out < 0) first = 0;
  if (in < 0) last = n - 1;
  if (first < 0 || last < 0 || ((in < 0 || out < 0) && !boundary) || (boundary && last < first))
    throw TopologyError("sigma_fields: walk " + std::to_string(k) + " cannot pass vertex " + std::to_string(p) +
                        " this way");
  for (int i = first;; i = (i + 1) % n) {
    const int f = fan[i].face, c = fan[i].corner;
    // ∇φ_p|t = (1/2A_t) J e, e the edge opposite p (thesis 1.2).
    entries.emplace_back(f, k, Complex(0, 1) * mesh.edge_vector_local(f, c) / (2 * mesh.face_areas()[f]));
    if (i == last) break;
  }
}

// All visits of the walk v_0 … v_m, accumulated into column k.
void add_walk(const Mesh& mesh, int k, std::span<const int> v, bool closed,
              std::vector<Eigen::Triplet<Complex>>& entries) {
  const int m = static_cast<int>(v.size()) - 1;
  if (m < 1) throw InputError("", 0, "sigma_fields: walk " + std::to_string(k) + " has no edge");
  if (closed) {
    if (v.front() != v.back())
      throw InputError("", 0, "sigma_fields: closed walk " + std::to_string(k) + " does not return to its start");
    for (int i = 0; i < m; ++i) add_visit(mesh, k, v[i], v[(i + m - 1) % m], v[i + 1], entries);
  } else {
    for (int i = 0; i <= m; ++i) add_visit(mesh, k, v[i], i > 0 ? v[i - 1] : -1, i < m ? v[i + 1] : -1, entries);
  }
}

}  // namespace

Eigen::SparseMatrix<Complex> sigma_fields(const Mesh& mesh, const HomologyBasis& basis) {
  std::vector<Eigen::Triplet<Complex>> entries;
  for (int k = 0; k < basis.size(); ++k)
    add_walk(mesh, k, basis.generators[k].vertices, basis.generators[k].closed, entries);
  Eigen::SparseMatrix<Complex> sigma(mesh.num_faces(), basis.size());
  sigma.setFromTriplets(entries.begin(), entries.end());
  return sigma;
}

Eigen::SparseVector<Complex> walk_sigma_field(const Mesh& mesh, std::span<const int> vertices, bool closed) {
  std::vector<Eigen::Triplet<Complex>> entries;
  add_walk(mesh, 0, vertices, closed, entries);
  Eigen::SparseMatrix<Complex> sigma(mesh.num_faces(), 1);
  sigma.setFromTriplets(entries.begin(), entries.end());
  return sigma.col(0);
}

VectorField sigma_field(const Eigen::SparseMatrix<Complex>& sigma, const Eigen::VectorXd& b) {
  if (b.size() != sigma.cols())
    throw InputError(
        "", 0,
        "sigma_field: " + std::to_string(b.size()) + " periods for " + std::to_string(sigma.cols()) + " generators");
  return sigma * b.cast<Complex>();
}

std::vector<VectorField> harmonic_basis(const HodgeDecomposer& hodge, const HomologyBasis& basis,
                                        const Eigen::SparseMatrix<Complex>& sigma) {
  std::vector<VectorField> H;
  H.reserve(static_cast<std::size_t>(basis.size()));
  for (int k = 0; k < basis.size(); ++k) {
    const VectorField S = sigma.col(k);
    H.push_back(S - gradient(hodge.mesh(), hodge.exact_potential(S)));  // H_k = Σ_k - ∇u, 𝔏u = -div Σ_k
  }
  return H;
}

VectorField harmonic_field_with_periods(const HodgeDecomposer& hodge, const HomologyBasis& basis,
                                        const Eigen::SparseMatrix<Complex>& sigma, const Eigen::VectorXd& b) {
  if (b.size() != basis.size())
    throw InputError("", 0,
                     "harmonic_field_with_periods: " + std::to_string(b.size()) + " periods for " +
                         std::to_string(basis.size()) + " generators");
  const VectorField S = sigma_field(sigma, b);
  return S - gradient(hodge.mesh(), hodge.exact_potential(S));  // (1.14)
}

}  // namespace quadcover
