#include "metrics/surface_distance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <cmath>
#include <optional>
#include <vector>

#include "mesh/triangle_tree.h"

namespace quadcover {

namespace {
// Distances from point(0..n-1) to the tree, queried in parallel; the caller reduces them in index order, so sums
// do not depend on the thread count.
template <class Point>
std::vector<double> distances(const TriangleTree& tree, int n, const Point& point) {
  std::vector<double> out(n);
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 256), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) out[i] = std::sqrt(tree.squared_distance(point(i)));
  });
  return out;
}
}  // namespace

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
  std::optional<TriangleTree> to_ref_tree, to_remesh_tree;  // the two builds are independent
  tbb::parallel_invoke([&] { to_ref_tree.emplace(ref_V, ref_F); }, [&] { to_remesh_tree.emplace(V, T); });
  const TriangleTree &to_ref = *to_ref_tree, &to_remesh = *to_remesh_tree;
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
  for (double dist : distances(to_ref, static_cast<int>(samples.size()), [&](int i) { return samples[i]; })) {
    sum += dist;
    d.max_to_reference = std::max(d.max_to_reference, dist);
  }
  d.mean_to_reference = sum / static_cast<double>(samples.size()) / d.bbox_diagonal;
  d.max_to_reference /= d.bbox_diagonal;
  sum = 0;
  const auto ref_point = [&](int v) -> Eigen::Vector3d { return ref_V.row(v).transpose(); };
  for (double dist : distances(to_remesh, static_cast<int>(ref_V.rows()), ref_point)) {
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
