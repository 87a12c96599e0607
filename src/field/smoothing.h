#pragma once
// Frame field smoothing (thesis 5.2.1, (5.3)-(5.4)) with a factorization reused across matching changes (5.2.2).
#include <Eigen/Core>
#include <memory>
#include <span>
#include <vector>

#include "field/frame_field.h"
#include "mesh/mesh.h"

namespace quadcover {

/// Minimizes E(α) = λ E_S(α) + (1-λ) E_A(α) (5.3) over per-face rotation angles α_t of an input field X⁰:
///   E_S(α) = Σ_e ω_e (θ_e - α_s + α_t)²,  ω_e = ‖e‖²/A_e, θ the curvature (3.4) of X⁰ with the current matching;
///   E_A(α) = Σ_{trusted t} a_t α_t²,  a_t = ω_t^stable A_t / mean_trusted(ω^stable A)  (thesis: ω_t^stable A_t;
///   we divide by its mean so that E_A, like E_S, is independent of the mesh's scale and λ means the same on
///   every mesh).
/// Faces marked `fixed` keep α_t = 0 (feature alignment). A connected group of free faces with neither a fixed
/// neighbour nor a positive alignment weight would leave A (5.4) singular (E is invariant under a common
/// rotation); its most stable face is then fixed as well.
///
/// A (5.4) does not depend on the matching: it is factored once in the constructor; change_matching() updates two
/// entries of b and solve() costs two triangular solves.
/// The smoother keeps a pointer to `mesh`, which must outlive it.
class FrameSmoother {
 public:
  /// \param input      X⁰ and its matching (Y is ignored; the result is a cross field)
  /// \param stability  #F stability weights ω_t (5.2)
  /// \param trusted    #F flags of the alignment term E_A
  /// \param fixed      #F flags of faces whose frame must not rotate (may be empty)
  /// \param lambda     λ ∈ (0, 1]
  /// \throw std::invalid_argument for λ outside (0,1] or wrong sizes; NumericalError if A cannot be factored.
  FrameSmoother(const Mesh& mesh, const FrameField& input, const Eigen::VectorXd& stability,
                const std::vector<char>& trusted, const std::vector<char>& fixed, double lambda);
  /// The same without X⁰: factors A (5.4), which depends only on the mesh, the weights and λ, so that the
  /// factorization can run while X⁰ is still being computed; set_input() must follow before solve(),
  /// change_matching(), rotated() and the energies (set_alignment_targets() may come before).
  /// \throw std::invalid_argument for λ outside (0,1] or wrong sizes; NumericalError if A cannot be factored.
  FrameSmoother(const Mesh& mesh, const Eigen::VectorXd& stability, const std::vector<char>& trusted,
                const std::vector<char>& fixed, double lambda);
  /// Sets X⁰ and its matching (θ and b; A is kept). Alignment targets set before stay in effect.
  /// \throw std::invalid_argument on wrong sizes.
  void set_input(const FrameField& input);
  ~FrameSmoother();
  FrameSmoother(FrameSmoother&&) noexcept;
  FrameSmoother& operator=(FrameSmoother&&) noexcept;

  /// m_e += k on interior edge e: θ_e becomes wrap(θ_e - (π/2)k) and only the two entries b_s, b_t change
  /// (5.2.2: by ∓λω_e(π/2)k when no wrap occurs). The result equals a smoother built from the new matching.
  /// \pre set_input() was called; 0 <= e < #E (a boundary edge or k = 0 changes nothing).
  void change_matching(int e, int k);
  /// Aligns E_A to target rotations instead of α = 0: E_A(α) = Σ_trusted a_t (α_t - β_t)² (beyond the thesis:
  /// lets E_A pull towards the curvature frames when X⁰ is not them, e.g. after the power fill). Like a matching
  /// change it only updates b. β  #F (entries of untrusted and fixed faces are ignored); all zeros restores (5.3).
  /// \throw std::invalid_argument if beta does not have #F entries.
  void set_alignment_targets(const Eigen::VectorXd& beta);
  /// The minimizer α of (5.3) for the current matching: #F, 0 at fixed faces.
  /// \pre set_input() was called. \throw NumericalError if the solve fails.
  Eigen::VectorXd solve() const;
  /// The minimizer of (5.3) for the matching after `changes` (m_e += delta, in order), given `alpha`, the minimizer
  /// for the current matching: α + A⁻¹δb, where δb is nonzero at the changed edges' faces only (5.2.2), so the
  /// forward substitution visits only their elimination-tree paths (the factor of A is prepared for that at the first
  /// call: SparseCholesky::prepare_sparse_solves). Equal to applying the changes and solve() up to round-off; the
  /// matching, θ and b are left exactly as they were.
  /// \pre set_input() was called; alpha has #F entries; every change names an edge.
  /// \throw NumericalError if the solve fails.
  Eigen::VectorXd solve_after(const Eigen::VectorXd& alpha, std::span<const MatchingChange> changes);
  /// X_t = e^{iα_t} X⁰_t with the current matching (a cross field). \pre set_input() was called; alpha has #F entries.
  FrameField rotated(const Eigen::VectorXd& alpha) const;

  double smoothing_energy(const Eigen::VectorXd& alpha) const;  ///< E_S(α) \pre set_input() was called; alpha #F
  double alignment_energy(const Eigen::VectorXd& alpha) const;  ///< E_A(α) with the current targets β \pre alpha #F

  const Eigen::VectorXi& matching() const { return matching_; }  ///< \pre none
  const Eigen::VectorXd& curvature() const { return theta_; }  ///< θ of X⁰ with the current matching, #E \pre none
  /// Faces held at α = 0: the `fixed` ones plus those fixed to make A definite. \pre none
  const std::vector<char>& fixed_faces() const { return fixed_; }
  int num_unknowns() const { return static_cast<int>(unknowns_.size()); }  ///< \pre none

  // The system A α = b of (5.4), for the optimizer's re-smoothing (optimize/local_smoothing.h).
  double lambda() const { return lambda_; }  ///< λ of (5.3) \pre none
  const Eigen::VectorXd& edge_weights() const { return omega_; }  ///< ω_e, #E \pre none
  const Eigen::VectorXd& alignment_weights() const { return align_; }  ///< a_t, #F (0 off the trusted faces) \pre none
  /// x = A⁻¹ r with the factorization of A: r and x per face (#F), 0 at the fixed faces.
  /// \pre r has #F entries. \throw NumericalError if the solve fails.
  Eigen::VectorXd solve_system(const Eigen::VectorXd& r) const;

 private:
  struct Solver;
  const Mesh* mesh_;
  Eigen::VectorXcd X0_;
  Eigen::VectorXi matching_;
  Eigen::VectorXd theta_, omega_, align_, beta_;  // θ_e, ω_e (#E); a_t, β_t (#F)
  double lambda_;
  std::vector<char> fixed_;
  std::vector<int> unknown_of_face_, unknowns_;
  Eigen::VectorXd b_;
  std::unique_ptr<Solver> solver_;
};

}  // namespace quadcover
