#pragma once
// The period matrix of the symmetric paths (thesis 6.3, 6.3.2). Rounding the periods b to lattice points c changes
// the harmonic correction H̃_d, d = c − b, and E_H = ‖H̃_d‖² (the Parameterization's convention: ½‖·‖² on M̃) is a
// quadratic form in the real and imaginary parts of d on the free paths: E_H = xᵀ P x,
// x = (Re d_{j_1}, …, Re d_{j_m}, Im d_{j_1}, …, Im d_{j_m}).
// P_ij = ⟨H_i, Σ_j⟩ = ⟨H_i, H_j⟩ (H_i ⟂ gradients): built column block by column block with one harmonic field
// H_i = Σ_i − ∇u_i at a time, the Σ_j stored sparsely (their support is the faces along the cut), and
// ⟨∇u_i, Σ_j⟩ = Re(u_iᴴ b_j) read off the sparse right-hand side b_j of Σ_j: no dense #F field per path. The
// imaginary unit acts on frame pairs as the quarter turn i(X, Y) = (−Y, X), so the Im columns need no extra solves.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "param/cut_fans.h"
#include "param/harmonic_correction.h"

namespace quadcover {

struct PeriodMatrix {
  std::vector<int> paths;  ///< the m free paths (each component's dependent path is fixed by its constant)
  Eigen::MatrixXd P;       ///< 2m by 2m, symmetric positive semi-definite: E_H = xᵀ P x
  long long sigma_support = 0;  ///< Σ_j |supp Σ_j| (faces), the sparse storage
  double asymmetry = 0;         ///< max |P_ij − P_ji| / max |P_ii| before symmetrization (round-off)
};

/// Σ̃_j = ∇σ_j for the unit jump on path j (completed to the whole cut), per face as frame pairs; only the faces
/// in `support` are non-zero.
struct SparseJumpField {
  std::vector<int> support;
  std::vector<Complex> X, Y;  ///< per support face
};
/// \pre cut = build_cover_cut(mesh, …); 0 <= path < cut.num_paths().
SparseJumpField unit_jump_field(const Mesh& mesh, const CoverCut& cut, int path);

/// Memory unit_jump_field reuses from path to path: all zero between calls, so a call costs the walk of the cut
/// and the support, not #E + 3·#F values.
struct JumpScratch {
  Eigen::VectorXcd c;       ///< #E translations
  Eigen::MatrixX3cd sigma;  ///< #F by 3 jump values
};
/// The same with the cut's fans made once. \pre fans = cut_fans(mesh, cut); 0 <= path < cut.num_paths().
SparseJumpField unit_jump_field(const Mesh& mesh, const CoverCut& cut, const CutFans& fans, int path,
                                JumpScratch& scratch);

/// Right-hand sides per block of period_matrix() on a mesh of `num_vertices`: 32, fewer on large meshes so that one
/// dense #V block of them stays within 32 MB (a solve holds three such blocks besides the factor, and a block is
/// solved per thread at once), at least 4. Wider blocks amortize the supernodal solve's packing of the factor's
/// blocks over more columns (BENCHMARKS.md, "Period matrix on many paths").
/// \pre num_vertices >= 0
int period_block_columns(int num_vertices);

/// P for the free paths of `cut`; `correction` must have been built for the same cut. Solves in blocks of
/// `block_size` right-hand sides (0: period_block_columns); `stop` (if set) is asked between blocks, and a stopped
/// computation returns an empty `paths` (no matrix). \throw NumericalError if a solve fails.
PeriodMatrix period_matrix(const Mesh& mesh, const CoverCut& cut, const HarmonicCorrection& correction,
                           int block_size = 0, const std::function<bool()>& stop = {});

}  // namespace quadcover
