#pragma once
// Test helper: the map's winding around every vertex, recomputed directly from the corner coordinates (an
// independent check of param/ring_winding.h map_quarter_index and pipeline/validity_retries.h).
#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <numbers>

#include "mesh/mesh.h"

namespace quadcover::testing {

/// 4·(1 − Θ_v / 2π) rounded per vertex, Θ_v the sum of the signed corner angles arg((c − a) / (b − a)) of φ at v
/// (boundary vertices included: there it is not a winding). \pre uv is #F by 3.
inline Eigen::VectorXi quarter_index_by_angle_sums(const Mesh& mesh, const Eigen::MatrixX3cd& uv) {
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const std::complex<double> a = uv(f, c), b = uv(f, (c + 1) % 3), d = uv(f, (c + 2) % 3);
      if (b != a && d != a) theta[mesh.F()(f, c)] += std::arg((d - a) / (b - a));
    }
  Eigen::VectorXi q(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v)
    q[v] = static_cast<int>(std::lround(4 * (1 - theta[v] / (2 * std::numbers::pi))));
  return q;
}

}  // namespace quadcover::testing
