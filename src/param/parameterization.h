#pragma once
// The result of the QuadCover parameterization (thesis Chapters 2 and 4): a seamless integer-grid map.
#include <Eigen/Core>
#include <vector>

#include "field/frame_field.h"
#include "mesh/mesh.h"

namespace quadcover {

struct Parameterization {
  /// #F by 3: φ = φ⁰ + iφ¹ at each corner (CornerData), in grid units: integer iso-lines are the quad edges.
  Eigen::MatrixX3cd uv;
  /// Per edge e (s = EF(e,0), t = EF(e,1)): across e the coordinates satisfy φ_t = i^{rotation_e} φ_s + translation_e,
  /// with translation_e ∈ Z[i] (the seamless transition). Both 0 where φ is continuous and on boundary edges.
  Eigen::VectorXi transition_rotation;      ///< #E, in 0..3
  Eigen::VectorXcd transition_translation;  ///< #E
  /// Edges of the cut along which φ may jump (#E, 1 = cut).
  Eigen::VectorXi cut_edges;
  /// Branch points of the guiding field (vertices with non-integer index).
  std::vector<BranchPoint> branch_points;
  /// Energies (thesis 6.1.1): E_D = ½‖X_C‖² (curl part removed), E_H (harmonic correction).
  double energy_curl = 0, energy_harmonic = 0;
};

}  // namespace quadcover
