// Hodge decomposition (thesis 1.2.3-1.2.4): (1.8), (1.9) solved with factorizations computed once, the constant
// kernel removed by pinning and the normalization (1.10). See hodge.h for the boundary conditions.
#include "calculus/hodge.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "calculus/div_curl.h"
#include "calculus/gradient.h"
#include "calculus/sparse_cholesky.h"
#include "calculus/stiffness.h"

namespace quadcover {

namespace {

/// A stiffness system with the kernel removed: per component either one pinned element (constant kernel,
/// rhs projected to the range, solution normalized to ∫ = 0) or a set of Dirichlet elements fixed to zero.
class ReducedSystem {
 public:
  /// K: n by n stiffness; component: per element; has_kernel: per component; dirichlet: per element (1 = fixed).
  ReducedSystem(const Eigen::SparseMatrix<double>& K, std::vector<int> component, std::vector<char> has_kernel,
                const std::vector<char>& dirichlet, Eigen::VectorXd weight, CholeskyBackend backend, const char* stage)
      : component_(std::move(component)),
        has_kernel_(std::move(has_kernel)),
        weight_(std::move(weight)),
        chol_(backend) {
    const auto n = static_cast<int>(K.rows());
    index_.assign(static_cast<std::size_t>(n), -1);
    std::vector<char> pinned(has_kernel_.size(), 0);
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const int c = component_[i];
      if (dirichlet[i]) continue;
      if (has_kernel_[c] && !pinned[c]) {  // the first element of a component with a constant kernel: u_i = 0
        pinned[c] = 1;
        continue;
      }
      index_[i] = m++;
    }
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(static_cast<std::size_t>(K.nonZeros()));
    for (int col = 0; col < K.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(K, col); it; ++it) {
        const int r = index_[it.row()], c = index_[it.col()];
        if (r >= 0 && c >= 0) t.emplace_back(r, c, it.value());
      }
    Eigen::SparseMatrix<double> R(m, m);
    R.setFromTriplets(t.begin(), t.end());
    chol_.compute(R, stage);
    component_weight_.setZero(static_cast<Eigen::Index>(has_kernel_.size()));
    component_count_.setZero(static_cast<Eigen::Index>(has_kernel_.size()));
    for (int i = 0; i < n; ++i) {
      component_weight_[component_[i]] += weight_[i];
      component_count_[component_[i]] += 1;
    }
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const {
    const auto n = static_cast<Eigen::Index>(index_.size());
    if (rhs.size() != n)
      throw std::invalid_argument("Hodge solve: right-hand side has " + std::to_string(rhs.size()) +
                                  " entries, expected " + std::to_string(n));
    const auto nc = static_cast<Eigen::Index>(has_kernel_.size());
    // Project to the range of K: remove the mean per component with a constant kernel.
    Eigen::VectorXd mean = Eigen::VectorXd::Zero(nc);
    for (Eigen::Index i = 0; i < n; ++i) mean[component_[i]] += rhs[i];
    for (Eigen::Index c = 0; c < nc; ++c) mean[c] = has_kernel_[c] ? mean[c] / component_count_[c] : 0.0;
    Eigen::VectorXd reduced(chol_.rows());
    for (Eigen::Index i = 0; i < n; ++i)
      if (index_[i] >= 0) reduced[index_[i]] = rhs[i] - mean[component_[i]];
    const Eigen::VectorXd x = chol_.solve(reduced);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i = 0; i < n; ++i)
      if (index_[i] >= 0) u[i] = x[index_[i]];
    // (1.10): ∫u dA = Σ_i u_i ∫(basis_i) = 0 per component with a constant kernel.
    Eigen::VectorXd integral = Eigen::VectorXd::Zero(nc);
    for (Eigen::Index i = 0; i < n; ++i) integral[component_[i]] += weight_[i] * u[i];
    for (Eigen::Index i = 0; i < n; ++i) {
      const int c = component_[i];
      if (has_kernel_[c]) u[i] -= integral[c] / component_weight_[c];
    }
    return u;
  }

 private:
  std::vector<int> component_;
  std::vector<char> has_kernel_;
  Eigen::VectorXd weight_, component_weight_, component_count_;
  std::vector<int> index_;  ///< element -> reduced row, -1 if pinned or Dirichlet
  SparseCholesky<double> chol_;
};

ReducedSystem conforming_system(const Mesh& mesh, CholeskyBackend backend) {
  const int nv = mesh.num_vertices();
  std::vector<int> component(static_cast<std::size_t>(nv));
  for (int v = 0; v < nv; ++v) component[v] = mesh.vertex_component()[v];
  // Natural boundary conditions: every component has the constant kernel.
  std::vector<char> has_kernel(static_cast<std::size_t>(mesh.num_components()), 1);
  return ReducedSystem(conforming_stiffness(mesh), std::move(component), std::move(has_kernel),
                       std::vector<char>(static_cast<std::size_t>(nv), 0), vertex_areas(mesh), backend,
                       "Hodge decomposition: conforming stiffness");
}

ReducedSystem nonconforming_system(const Mesh& mesh, CholeskyBackend backend) {
  const int ne = mesh.num_edges();
  std::vector<int> component(static_cast<std::size_t>(ne));
  std::vector<char> dirichlet(static_cast<std::size_t>(ne), 0);
  for (int e = 0; e < ne; ++e) {
    const int f = mesh.face_of_edge(e);
    component[e] = mesh.face_component()[f];
    dirichlet[e] = mesh.is_boundary_edge(e) ? 1 : 0;  // v = 0 on boundary edges
  }
  std::vector<char> has_kernel(static_cast<std::size_t>(mesh.num_components()));
  for (int c = 0; c < mesh.num_components(); ++c) has_kernel[c] = mesh.components()[c].boundary_loops == 0;
  return ReducedSystem(nonconforming_stiffness(mesh), std::move(component), std::move(has_kernel), dirichlet,
                       edge_areas(mesh), backend, "Hodge decomposition: nonconforming stiffness");
}

}  // namespace

struct HodgeDecomposer::Impl {
  Impl(const Mesh& m, CholeskyBackend backend)
      : mesh(m), conforming(conforming_system(m, backend)), nonconforming(nonconforming_system(m, backend)) {}
  const Mesh& mesh;
  ReducedSystem conforming, nonconforming;
};

HodgeDecomposer::HodgeDecomposer(const Mesh& mesh, const HodgeOptions& options)
    : impl_(std::make_unique<Impl>(mesh, options.backend)) {}
HodgeDecomposer::~HodgeDecomposer() = default;
HodgeDecomposer::HodgeDecomposer(HodgeDecomposer&&) noexcept = default;

const Mesh& HodgeDecomposer::mesh() const { return impl_->mesh; }

Eigen::VectorXd HodgeDecomposer::solve_conforming(const Eigen::VectorXd& rhs) const {
  return impl_->conforming.solve(rhs);
}

Eigen::VectorXd HodgeDecomposer::solve_nonconforming(const Eigen::VectorXd& rhs) const {
  return impl_->nonconforming.solve(rhs);
}

Eigen::VectorXd HodgeDecomposer::exact_potential(const VectorField& X) const {
  return solve_conforming(-divergence(impl_->mesh, X));  // (1.8)
}

Eigen::VectorXd HodgeDecomposer::coexact_potential(const VectorField& X) const {
  return solve_nonconforming(-curl_star(impl_->mesh, X));  // (1.9)
}

HodgeParts HodgeDecomposer::decompose(const VectorField& X) const {
  const Mesh& mesh = impl_->mesh;
  HodgeParts parts;
  parts.potential = exact_potential(X);
  parts.copotential = coexact_potential(X);
  parts.exact = gradient(mesh, parts.potential);
  parts.coexact = Complex(0, 1) * nonconforming_gradient(mesh, parts.copotential);  // J∇v
  parts.harmonic = X - parts.exact - parts.coexact;
  return parts;
}

}  // namespace quadcover
