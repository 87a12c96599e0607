#include "topology/integrate.h"

#include <string>

#include "common/errors.h"

namespace quadcover {

Eigen::VectorXd integrate_cut_vertices(const Mesh& mesh, const CutMesh& cut, const VectorField& X) {
  const int nf = mesh.num_faces();
  if (X.size() != nf)
    throw InputError("", 0,
                     "integrate: field has " + std::to_string(X.size()) + " faces, mesh has " + std::to_string(nf));
  Eigen::VectorXd u = Eigen::VectorXd::Zero(cut.num_vertices());
  std::vector<char> known(static_cast<std::size_t>(cut.num_vertices()), 0);
  std::vector<char> reached(static_cast<std::size_t>(nf), 0);
  // ⟨q - p, X_f⟩ for corners a -> b of face f (1.12).
  auto delta = [&](int f, int a, int b) {
    const Complex d = mesh.corner_local()(f, b) - mesh.corner_local()(f, a);
    return (std::conj(X[f]) * d).real();
  };
  // Sets the unknown corner values of f from a known corner.
  auto complete_face = [&](int f) {
    int a = 0;
    while (!known[cut.corner_vertex(f, a)]) ++a;
    for (int b = 0; b < 3; ++b) {
      const int v = cut.corner_vertex(f, b);
      if (known[v]) continue;
      u[v] = u[cut.corner_vertex(f, a)] + delta(f, a, b);
      known[v] = 1;
    }
  };
  std::vector<int> queue;
  queue.reserve(static_cast<std::size_t>(nf));
  for (int start = 0; start < nf; ++start) {
    if (reached[start]) continue;
    reached[start] = 1;
    const int v0 = cut.corner_vertex(start, 0);
    if (!known[v0]) {  // a new piece (a closed piece can share no cut-vertex with an earlier one)
      u[v0] = 0;
      known[v0] = 1;
    }
    queue.assign(1, start);
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int f = queue[q];
      complete_face(f);
      for (int k = 0; k < 3; ++k) {
        const int g = mesh.neighbor(f, k);
        if (g < 0 || reached[g]) continue;
        // Cross only edges along which the cut mesh is glued: both endpoints share their cut-vertex in f and g.
        bool glued = true;
        for (int c = 1; c <= 2; ++c) {
          const int v = cut.corner_vertex(f, (k + c) % 3);
          bool found = false;
          for (int j = 0; j < 3; ++j) found = found || cut.corner_vertex(g, j) == v;
          glued = glued && found;
        }
        if (!glued) continue;
        reached[g] = 1;
        queue.push_back(g);
      }
    }
  }
  return u;
}

Eigen::MatrixX3d integrate(const Mesh& mesh, const CutMesh& cut, const VectorField& X) {
  const Eigen::VectorXd u = integrate_cut_vertices(mesh, cut, X);
  Eigen::MatrixX3d phi(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) phi(f, k) = u[cut.corner_vertex(f, k)];
  return phi;
}

Eigen::MatrixX3cd integrate_frame(const Mesh& mesh, const CutMesh& cut, const VectorField& X, const VectorField& Y) {
  const Eigen::MatrixX3d p0 = integrate(mesh, cut, X), p1 = integrate(mesh, cut, Y);
  Eigen::MatrixX3cd phi(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) phi(f, k) = Complex(p0(f, k), p1(f, k));
  return phi;
}

}  // namespace quadcover
