#pragma once
// Distortion of a parameterization (thesis 6.1.1) and its validity as an integer-grid map (thesis 2.1, 4.2.2).
#include <map>
#include <vector>

#include "mesh/mesh.h"
#include "param/parameterization.h"

namespace quadcover {

struct ParamQualityOptions {
  /// Upper bin edges of the per-triangle ARAP histogram (a last bin collects everything above).
  std::vector<double> arap_bins = {0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 1.0};
};

struct ParamQuality {
  /// Global scale s applied before measuring: s² · (total |UV area|) = 3D area (the Table 7.1 normalization).
  double scale = 1;
  /// ARAP = ½ · area-weighted mean over triangles of min_{R ∈ SO(2)} ‖s·J_t − R‖²_F (6.1.1, normalized as above).
  double arap = 0;
  double arap_max = 0;
  double arap_p95 = 0;                 ///< 95th percentile of the per-triangle value (area weighted)
  std::vector<double> arap_per_face;   ///< #F: ½ min_R ‖s·J_t − R‖²_F
  std::vector<int> arap_histogram;     ///< counts per bin of ParamQualityOptions::arap_bins (+1 overflow bin)
  std::vector<double> arap_bins;
  /// Orientation (thesis 2.1 requirement 2) as in param/seams.h: A_uv < −τ·A_ref, |A_uv| ≤ τ·A_ref, their sum.
  int flipped_triangles = 0;
  int collapsed_triangles = 0;
  int non_positive_triangles = 0;
  double uv_area = 0;                  ///< Σ |area(φ(t))| before scaling (the quad count of a closed map)
  double energy_curl = 0, energy_harmonic = 0;  ///< E_D and E_H passed through from the Parameterization
  /// Cone points of the map: interior vertices whose signed parameter angle sum Θ ≠ 2π (flipped corners count
  /// negative, so Θ is the map's winding: a vertex folded out of its link has Θ = 0, index 4), by quarter index
  /// round(4 − 2Θ/π) (4·ind, the convention of FrameField), and their total.
  std::map<int, int> branch_points_by_index;
  int branch_points = 0;
  /// Seamlessness: max over interior edges and endpoints of |φ_t − (i^k φ_s + c)|, and max distance of c to Z[i].
  double max_transition_error = 0;
  double max_translation_defect = 0;
  /// Cone points off the grid: max distance of a cone vertex's φ to the nearest Gaussian integer.
  double max_branch_point_offset = 0;
};

/// Measures the map. \pre param.uv is #F by 3; transitions per edge (empty vectors mean identity everywhere).
ParamQuality param_quality(const Mesh& mesh, const Parameterization& param, const ParamQualityOptions& options = {});

/// Cone points of a map from its per-corner coordinates alone, the one computation behind `param`, `metrics`, the
/// reports and `render`: vertices with boundary[v] == 0 whose signed parameter angle sum Θ (a flipped corner counts
/// negative; a corner with a side of zero length adds nothing) differs from 2π, with quarter_index
/// round((2π − Θ) / (π/2)) = round(4 − 2Θ/π) = 4·ind_p (FrameField's convention).
/// \pre uv is #F by 3; boundary has an entry per vertex F uses.
std::vector<BranchPoint> cones_from_uv(const Eigen::MatrixX3i& F, const Eigen::MatrixX3cd& uv,
                                       const std::vector<char>& boundary);
/// The same, with the boundary vertices found from F (ends of an edge no triangle traverses the other way), for
/// triangles read from a file. Empty if uv does not have a row per face. \pre F indices >= 0.
std::vector<BranchPoint> cones_from_uv(const Eigen::MatrixX3i& F, const Eigen::MatrixX3cd& uv);

/// ½ min_{R ∈ SO(2)} ‖J − R‖²_F for a 2×2 matrix J = [[a, b], [c, d]]: ½(‖J‖² + 2 − 2·|(a+d, c−b)|). \pre none
double arap_density(const Eigen::Matrix2d& J);

/// Jacobian of φ on face f: maps the face's tangent basis coordinates (Mesh::corner_local) to φ.
/// \pre uv is #F by 3; 0 <= f < #F.
Eigen::Matrix2d map_jacobian(const Mesh& mesh, const Eigen::MatrixX3cd& uv, int f);

}  // namespace quadcover
