#include "metrics/vertex_quality.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace quadcover {

VertexQuality vertex_quality(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces) {
  const Eigen::Index nv = V.rows();
  VertexQuality q;
  q.worst_angle_deviation = Eigen::VectorXd::Zero(nv);
  q.valence = Eigen::VectorXi::Zero(nv);
  std::vector<std::pair<int, int>> edges;  // undirected, (min, max)
  for (const auto& f : faces) {
    const int n = static_cast<int>(f.size());
    const double regular = 180.0 * (n - 2) / n;
    for (int i = 0; i < n; ++i) {
      const int a = f[(i + n - 1) % n], b = f[i], c = f[(i + 1) % n];
      edges.emplace_back(std::min(b, c), std::max(b, c));
      const Eigen::Vector3d u = V.row(a) - V.row(b), w = V.row(c) - V.row(b);
      const double angle = u.norm() > 0 && w.norm() > 0
                               ? std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / std::numbers::pi
                               : regular + 180.0;
      double& worst = q.worst_angle_deviation[b];
      worst = std::max(worst, std::min(180.0, std::abs(angle - regular)));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const auto& [a, b] : edges) ++q.valence[a], ++q.valence[b];
  return q;
}

}  // namespace quadcover
