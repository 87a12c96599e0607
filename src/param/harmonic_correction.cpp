#include "param/harmonic_correction.h"

namespace quadcover {

void pin_rows(Eigen::SparseMatrix<Complex>& A, const std::vector<int>& rows) {
  if (rows.empty()) return;
  std::vector<char> pinned(static_cast<std::size_t>(A.rows()), 0);
  for (int r : rows) pinned[r] = 1;
  for (int c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<Complex>::InnerIterator it(A, c); it; ++it)
      if (pinned[it.row()] || pinned[it.col()]) it.valueRef() = it.row() == it.col() ? Complex(1) : Complex(0);
}

HarmonicCorrection::HarmonicCorrection(const Mesh& mesh, const CoverCut& cut, const std::vector<char>& trivial)
    : mesh_(&mesh), layers_(vertex_layers(mesh, cut.matching)), L_(complex_conforming_stiffness(mesh, cut.matching)) {
  std::vector<char> done(trivial.size(), 0);
  for (int p = 0; p < mesh.num_vertices(); ++p) {
    const int comp = mesh.vertex_component()[p];
    if (trivial[comp] && !done[comp]) {
      done[comp] = 1;
      kernel_pins_.push_back(p);
    }
  }
  Eigen::SparseMatrix<Complex> Lp = L_;
  pin_rows(Lp, kernel_pins_);
  chol_.compute(Lp, "harmonic correction (complex conforming stiffness)");
}

void HarmonicCorrection::add_rhs(int f, Complex X, Complex Y, Eigen::VectorXcd& b) const {
  const Mesh& mesh = *mesh_;
  for (int a = 0; a < 3; ++a) {
    const int p = mesh.F()(f, a);
    if (layers_.branch[p]) continue;
    // ∫⟨∇φ_p, Σ⟩ with ∇φ_p = J e_p / 2A, read in p's gauge.
    b[p] += ipow(-layers_.layer(f, a)) * 0.5 * frame_dot(Complex(0, 1) * mesh.edge_vector_local(f, a), X, Y);
  }
}

Eigen::VectorXcd HarmonicCorrection::rhs(const FramePairs& Sigma, const std::vector<int>& faces) const {
  Eigen::VectorXcd b = Eigen::VectorXcd::Zero(mesh_->num_vertices());
  for (int f : faces) add_rhs(f, Sigma(f, 0), Sigma(f, 1), b);
  return b;
}

Eigen::VectorXcd HarmonicCorrection::rhs(const std::vector<int>& faces, const std::vector<Complex>& X,
                                         const std::vector<Complex>& Y) const {
  Eigen::VectorXcd b = Eigen::VectorXcd::Zero(mesh_->num_vertices());
  for (std::size_t k = 0; k < faces.size(); ++k) add_rhs(faces[k], X[k], Y[k], b);
  return b;
}

Eigen::VectorXcd HarmonicCorrection::rhs(const FramePairs& Sigma) const {
  std::vector<int> all(static_cast<std::size_t>(mesh_->num_faces()));
  for (int f = 0; f < mesh_->num_faces(); ++f) all[f] = f;
  return rhs(Sigma, all);
}

Eigen::MatrixXcd HarmonicCorrection::solve(Eigen::MatrixXcd B) const {
  for (int p : kernel_pins_) B.row(p).setZero();
  return chol_.solve(B);
}

void HarmonicCorrection::release_factor() { chol_ = SparseCholesky<Complex>(chol_.backend()); }

Eigen::MatrixX3cd HarmonicCorrection::corner_values(const Eigen::VectorXcd& u) const {
  return layered_values(*mesh_, layers_, u);
}

FramePairs HarmonicCorrection::harmonic_part(const FramePairs& Sigma) const {
  const Eigen::VectorXcd u = solve(rhs(Sigma)).col(0);
  return Sigma - corner_gradient(*mesh_, corner_values(u));
}

double frame_norm2(const Mesh& mesh, const FramePairs& Z) {
  double s = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) s += mesh.face_areas()[f] * (std::norm(Z(f, 0)) + std::norm(Z(f, 1)));
  return s;
}

double frame_inner(const Mesh& mesh, const FramePairs& Z, const FramePairs& W) {
  double s = 0;
  for (int f = 0; f < mesh.num_faces(); ++f)
    s += mesh.face_areas()[f] * std::real(std::conj(Z(f, 0)) * W(f, 0) + std::conj(Z(f, 1)) * W(f, 1));
  return s;
}

}  // namespace quadcover
