#include "field/curvature_frames.h"

#include <cmath>
#include <vector>

#include "mesh/shape_operator.h"

namespace quadcover {

namespace {

// A symmetric 2×2 tensor [[a,b],[b,c]] in a face basis, stored as its trace a + c and its deviator
// q = (a - c)/2 + i b. Eigenvalues (a + c)/2 ± |q|; the larger one's eigenvector has angle arg(q)/2.
struct Tensor2 {
  double trace = 0;
  Complex q = 0;
  void add_outer(Complex w, double weight) {  // weight · w wᵀ: trace |w|², deviator w²/2
    trace += weight * std::norm(w);
    q += 0.5 * weight * w * w;
  }
};

void store(CurvatureFrames& out, int t, const Tensor2& T) {
  const double r = std::abs(T.q);
  out.kappa_max[t] = 0.5 * T.trace + r;
  out.kappa_min[t] = 0.5 * T.trace - r;
  out.direction[t] = r > 0 ? std::polar(1.0, 0.5 * std::arg(T.q)) : Complex(1, 0);
}

Tensor2 project(const Mesh& mesh, int t, const Eigen::Matrix3d& S) {
  const Eigen::Vector3d b1 = mesh.face_basis1().row(t), b2 = mesh.face_basis2().row(t);
  const double a = b1.dot(S * b1), b = b1.dot(S * b2), c = b2.dot(S * b2);
  return {a + c, Complex(0.5 * (a - c), b)};
}

void hildebrandt_polthier(const Mesh& mesh, CurvatureFrames& out) {
  const std::vector<Eigen::Matrix3d> Sv = vertex_shape_operators(mesh);
  Eigen::VectorXd Av = Eigen::VectorXd::Zero(mesh.num_vertices());  // barycentric vertex areas ⅓ Σ A_t
  for (int t = 0; t < mesh.num_faces(); ++t)
    for (int k = 0; k < 3; ++k) Av[mesh.F()(t, k)] += mesh.face_areas()[t] / 3.0;
  for (int t = 0; t < mesh.num_faces(); ++t) {
    Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const int p = mesh.F()(t, k);
      S += Sv[static_cast<std::size_t>(p)] / (3.0 * Av[p]);  // pointwise operator at p, averaged over the face
    }
    store(out, t, project(mesh, t, S));
  }
}

void cohen_steiner_morvan(const Mesh& mesh, double radius, CurvatureFrames& out) {
  const int nf = mesh.num_faces();
  const Eigen::VectorXd beta = signed_dihedral_angles(mesh);
  Eigen::MatrixX3d C(nf, 3);
  for (int t = 0; t < nf; ++t)
    C.row(t) = (mesh.V().row(mesh.F()(t, 0)) + mesh.V().row(mesh.F()(t, 1)) + mesh.V().row(mesh.F()(t, 2))) / 3.0;
  std::vector<int> stamp(static_cast<std::size_t>(nf), -1), queue;
  const double r2 = radius * radius;
  for (int t = 0; t < nf; ++t) {
    queue.assign(1, t);
    stamp[static_cast<std::size_t>(t)] = t;
    Tensor2 T;
    double area = 0;
    for (std::size_t i = 0; i < queue.size(); ++i) {
      const int f = queue[i];
      area += mesh.face_areas()[f];
      for (int k = 0; k < 3; ++k) {
        const int e = mesh.FE()(f, k);
        // Each face carries half of each of its edges, so an edge inside the disk counts fully.
        if (beta[e] != 0) {
          const Eigen::Vector3d d = (mesh.V().row(mesh.E()(e, 1)) - mesh.V().row(mesh.E()(e, 0))).normalized();
          // β‖e‖ ê êᵀ measures curvature across e; turned by J it is the curvature tensor in t's plane.
          T.add_outer(Complex(0, 1) * mesh.to_local(t, d), 0.5 * beta[e] * mesh.edge_lengths()[e]);
        }
        const int g = mesh.neighbor(f, k);
        if (g < 0 || stamp[static_cast<std::size_t>(g)] == t) continue;
        if ((C.row(g) - C.row(t)).squaredNorm() > r2) continue;
        stamp[static_cast<std::size_t>(g)] = t;
        queue.push_back(g);
      }
    }
    T.trace /= area;
    T.q /= area;
    store(out, t, T);
  }
}

}  // namespace

CurvatureFrames principal_curvature_frames(const Mesh& mesh, const CurvatureOptions& options) {
  const int nf = mesh.num_faces();
  CurvatureFrames out;
  out.direction.resize(nf);
  out.kappa_max.resize(nf);
  out.kappa_min.resize(nf);
  if (options.method == CurvatureMethod::HildebrandtPolthier)
    hildebrandt_polthier(mesh, out);
  else
    cohen_steiner_morvan(mesh, options.csm_radius * mesh.mean_edge_length(), out);
  return out;
}

}  // namespace quadcover
