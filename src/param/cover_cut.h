#pragma once
// The cut of M through the base set B = branch points ∪ boundary vertices (thesis 4.2) and the gauge in which the
// covering functions become ordinary functions on the cut disk.
//
// Cut graph: Algorithm 1.16 with base sets (topology/cut_graph.h); its n paths σ(e_j) lift to the symmetric loops
// l̃_j^k = γ̃_j^k ∪ γ̃_j^{k+2} (4.2). Gauge: every face frame is turned by a quarter-turn power, Z'_f = i^{r_f} Z_f
// (frame-complex i, see cover/complex_stiffness.h), so that the matching is ≡ 0 mod 4 on every uncut interior edge.
// A covering function is then one complex function on the cut disk, and across each cut edge e
// (s = EF(e,0), t = EF(e,1)) its two sides satisfy φ_t = i^{k_e} φ_s + c_e, k_e = -m'_e mod 4 (the transition).
#include <Eigen/Core>
#include <vector>

#include "common/quarter_turn.h"
#include "field/frame_field.h"
#include "topology/cut_graph.h"
#include "topology/cut_mesh.h"

namespace quadcover {

/// One step of the walk around a vertex: from face `from` across `edge` into face `to`, counter-clockwise.
struct FanCrossing {
  int from, to, edge;
};
/// The crossings around v in counter-clockwise fan order: d for an interior vertex (closing the cycle),
/// d - 1 for a boundary vertex (the fan is open). \pre 0 <= v < #V
std::vector<FanCrossing> fan_crossings(const Mesh& mesh, int v);

struct CoverCut {
  CutGraph graph;  ///< the cut graph based at B (its sources are B ∪ ∂M ∪ one root per closed base-free component)
  CutMesh disk;    ///< M cut along graph.cut: one topological disk per component
  Eigen::VectorXi face_rotation;  ///< #F: r_f, Z'_f = i^{r_f} Z_f
  Eigen::VectorXi matching;       ///< #E: m'_e = m_e + r_s - r_t, ≡ 0 mod 4 on uncut interior edges
  Eigen::VectorXi rotation;       ///< #E: k_e = -m'_e mod 4 on cut edges, 0 elsewhere
  Eigen::VectorXi quarter_index;  ///< #V: 4·ind_p(m) (Def. 3.2); field/indices.h convention
  Eigen::VectorXi branch;         ///< #V: 1 iff quarter_index ≠ 0 mod 4
  int b_even = 0, b_odd = 0;
  /// Per path j of graph.paths: its leftover edge e_j (the edge where the dual cycle γ_j^* crosses the cut).
  std::vector<int> path_edge;
  /// Per path: the component of M it lies in.
  std::vector<int> path_component;
  /// Per component of M: the path whose period is fixed by the component's constant (the dependent n-th path of
  /// 4.2, one with k ≠ 0), or -1 when every transition of the component is a pure translation.
  std::vector<int> dependent_path;

  int num_paths() const { return static_cast<int>(path_edge.size()); }  ///< \pre none
  /// Number of real symmetric periods that are rounded: 2·(n - #dependent paths); equals h_sym of (4.1). \pre none
  int h_sym() const;
};

/// Cuts M through its branch points and boundary and computes the gauge.
/// \pre matching has #E entries. \throw NumericalError if the gauge does not close (inconsistent matching).
CoverCut build_cover_cut(const Mesh& mesh, const Eigen::VectorXi& matching);

/// h_sym of (4.1) for a connected surface: 4g + 2(b_even + b_odd) - 4 when there are branch points; 4g
/// without branch points (the b_odd = b_even = 0 case: four copies of M, 2g complex periods). With L > 0 boundary
/// loops (beyond the thesis), each loop acts like one more base point: 4g + 2(b + L) - 4, or 4g + 2L - 2 without
/// branch points (trivial holonomy: no path is fixed by the constant). \pre genus, b_even, b_odd, boundary_loops >= 0.
int symmetric_period_count(int genus, int b_even, int b_odd, int boundary_loops = 0);

/// The frame Z = (X, Y) turned by the frame-complex i^k: i(X, Y) = (-Y, X). \pre none
inline std::pair<Complex, Complex> turn_frame(Complex X, Complex Y, int k) {
  switch (mod4(k)) {
    case 0: return {X, Y};
    case 1: return {-Y, X};
    case 2: return {-X, -Y};
    default: return {Y, -X};
  }
}

}  // namespace quadcover
