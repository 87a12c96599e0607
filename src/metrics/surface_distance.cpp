#include "metrics/surface_distance.h"

#include <cmath>
#include <vector>

#include "mesh/triangle_tree.h"

namespace quadcover {

SurfaceDistance surface_distance(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces,
                                 const Eigen::MatrixX3d& ref_V, const Eigen::MatrixX3i& ref_F) {
  SurfaceDistance d;
  Eigen::AlignedBox3d box;
  for (int i = 0; i < ref_V.rows(); ++i) box.extend(ref_V.row(i).transpose());
  d.bbox_diagonal = ref_V.rows() ? box.diagonal().norm() : 0;
  if (d.bbox_diagonal <= 0 || faces.empty()) return d;
  // Fan triangulation of the polygons.
  std::vector<Eigen::Vector3i> tris;
  for (const auto& f : faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) tris.push_back({f[0], f[i], f[i + 1]});
  Eigen::MatrixX3i T(tris.size(), 3);
  for (std::size_t i = 0; i < tris.size(); ++i) T.row(i) = tris[i].transpose();
  const TriangleTree to_ref(ref_V, ref_F), to_remesh(V, T);
  // Samples of the remesh.
  std::vector<Eigen::Vector3d> samples;
  std::vector<char> used(V.rows(), 0);
  for (const auto& f : faces) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < f.size(); ++i) {
      used[f[i]] = 1;
      c += V.row(f[i]).transpose();
      if (f[i] < f[(i + 1) % f.size()])
        samples.push_back(0.5 * (V.row(f[i]) + V.row(f[(i + 1) % f.size()])).transpose());
    }
    samples.push_back(c / static_cast<double>(f.size()));
  }
  for (int v = 0; v < V.rows(); ++v)
    if (used[v]) samples.push_back(V.row(v).transpose());
  double sum = 0;
  for (const auto& p : samples) {
    const double dist = std::sqrt(to_ref.squared_distance(p));
    sum += dist;
    d.max_to_reference = std::max(d.max_to_reference, dist);
  }
  d.mean_to_reference = sum / static_cast<double>(samples.size()) / d.bbox_diagonal;
  d.max_to_reference /= d.bbox_diagonal;
  sum = 0;
  for (int v = 0; v < ref_V.rows(); ++v) {
    const double dist = std::sqrt(to_remesh.squared_distance(ref_V.row(v).transpose()));
    sum += dist;
    d.max_from_reference = std::max(d.max_from_reference, dist);
  }
  d.mean_from_reference = sum / static_cast<double>(ref_V.rows()) / d.bbox_diagonal;
  d.max_from_reference /= d.bbox_diagonal;
  d.mean = 0.5 * (d.mean_to_reference + d.mean_from_reference);
  d.max = std::max(d.max_to_reference, d.max_from_reference);
  return d;
}

}  // namespace quadcover
