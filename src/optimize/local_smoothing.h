#pragma once
// The smoothing system A α = b of (5.4) as seen by the optimizer: local re-smoothing after a matching change
// (beyond the thesis, which re-solves the whole f×f system for every E_D evaluation, 6.2.1 / Table 6.1).
//
// A matching change m_e += k changes only b_s, b_t by ∓λω_e·d (5.2.2, d = θ_e - wrap(θ_e - (π/2)k)), so the
// re-smoothed angles are α + Δα with A Δα = Δb. Δα is concentrated around e (A is a screened Laplacian: the
// alignment weights (1-λ)a_t damp it). solve_local() solves A_PP Δα_P = Δb_P on the faces P within a few rings
// of the changed edges (zero outside P, conjugate gradients); the far field is accounted for to first order by
// the caller with an adjoint vector z = A⁻¹ g (CurlEnergy).
#include <Eigen/Core>
#include <span>
#include <vector>

#include "field/smoothing.h"
#include "mesh/mesh.h"

namespace quadcover {

struct FaceEntry {
  int face;
  double value;
};

/// Per-thread scratch of solve_local (stamps instead of O(F) clears).
struct LocalSmoothingWork {
  std::vector<int> stamp, local;  // face -> stamp / local index
  int current = 0;
  std::vector<int> faces;  // patch faces in BFS order
  std::vector<double> x, r, p, q, diag;
};

class SmoothingSystem {
 public:
  /// The smoother's A (5.4): its weights, fixed faces and factorization (no copy of the matrix is assembled).
  /// \pre smoother outlives this. \throw std::invalid_argument if the smoother was built for another mesh.
  SmoothingSystem(const Mesh& mesh, const FrameSmoother& smoother);

  /// Δb of m_e += k given the current θ_e (5.2.2): {(s, -λω_e d), (t, +λω_e d)} for free s, t; θ_e is updated to
  /// the wrapped value so that repeated changes of one edge compose. \return number of entries written (0..2).
  /// \pre 0 <= e < #E
  int rhs_change(int e, int k, double& theta_e, FaceEntry out[2]) const;
  /// Δα = A⁻¹ Δb on all faces (the smoother's factorization: two triangular solves); 0 at fixed faces.
  /// \pre rhs has #F entries. \throw NumericalError if the solve fails.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  /// Δα on the patch of free faces within `rings` face-rings of the faces of `rhs` (Dirichlet 0 outside), by
  /// Jacobi-preconditioned conjugate gradients to relative residual `tol`. Results in work.faces / work.x.
  /// \pre rings >= 0, tol > 0; rhs faces in [0, #F).
  void solve_local(std::span<const FaceEntry> rhs, int rings, double tol, LocalSmoothingWork& work) const;
  /// y = A x (free faces; x, y #F, fixed entries ignored / 0). \pre x has #F entries.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;
  bool is_free(int f) const { return !fixed_[static_cast<std::size_t>(f)]; }  ///< \pre 0 <= f < #F

 private:
  const Mesh* mesh_;
  const FrameSmoother* smoother_;  // its A (5.4) and factorization: solve()
  double lambda_;
  const Eigen::VectorXd& omega_;     // the smoother's ω_e (#E)
  const std::vector<char>& fixed_;   // the smoother's fixed faces (#F)
  Eigen::VectorXd diag_;             // A_tt (#F, 0 at fixed faces), the Jacobi preconditioner of solve_local
};

}  // namespace quadcover
