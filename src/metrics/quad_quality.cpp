#include "metrics/quad_quality.h"

#include <cmath>
#include <set>
#include <unordered_map>
#include <unordered_set>

namespace quadcover {

double relative_std_percent(const std::vector<double>& x) {
  if (x.empty()) return 0;
  double mean = 0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  double var = 0;
  for (double v : x) var += (v - mean) * (v - mean);
  var /= static_cast<double>(x.size());
  return mean > 0 ? 100.0 * std::sqrt(var) / mean : 0;
}

QuadQuality quad_quality(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces) {
  QuadQuality q;
  const int nv = static_cast<int>(V.rows());
  q.topology = surface_counts(nv, faces);
  q.vertices = q.topology.vertices;
  q.faces = static_cast<int>(faces.size());
  std::unordered_map<long long, int> edge_use;  // undirected edge -> faces
  auto key = [](int a, int b) {
    if (a > b) std::swap(a, b);
    return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b);
  };
  std::vector<double> lengths, angles;
  for (const auto& f : faces) {
    const int n = static_cast<int>(f.size());
    ++q.face_sizes[n];
    if (n == 4) ++q.quads;
    for (int i = 0; i < n; ++i) {
      const int a = f[(i + n - 1) % n], b = f[i], c = f[(i + 1) % n];
      if (edge_use[key(b, c)]++ == 0) lengths.push_back((V.row(c) - V.row(b)).norm());
      const Eigen::Vector3d u = V.row(a) - V.row(b), w = V.row(c) - V.row(b);
      const double nu = u.norm(), nw = w.norm();
      if (nu > 0 && nw > 0) angles.push_back(std::atan2(u.cross(w).norm(), u.dot(w)));
    }
  }
  q.non_quads = q.faces - q.quads;
  q.rsd_edge_length = relative_std_percent(lengths);
  q.rsd_corner_angle = relative_std_percent(angles);
  for (double l : lengths) q.mean_edge_length += l / static_cast<double>(lengths.size());
  for (double a : angles) q.mean_corner_angle += a / static_cast<double>(angles.size());
  // Valence = number of distinct edges at a vertex; boundary vertices have an edge used by one face.
  std::vector<int> valence(nv, 0);
  std::vector<char> boundary(nv, 0), used(nv, 0);
  for (const auto& [k, count] : edge_use) {
    const int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffff);
    ++valence[a], ++valence[b];
    if (count == 1) boundary[a] = boundary[b] = 1;
  }
  for (const auto& f : faces)
    for (int v : f) used[v] = 1;
  for (int v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    if (boundary[v]) {
      ++q.boundary_vertices;
      if (valence[v] != 2 && valence[v] != 3) ++q.irregular_boundary_vertices;
    } else {
      ++q.valence_histogram[valence[v]];
      if (valence[v] != 4) ++q.irregular_vertices;
    }
  }
  return q;
}

}  // namespace quadcover
