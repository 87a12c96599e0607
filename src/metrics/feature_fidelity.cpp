#include "metrics/feature_fidelity.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/errors.h"
#include "mesh/segment_grid.h"

namespace quadcover {

namespace {

// The distinct undirected edges of the polygons, as (min, max) pairs in ascending order.
Eigen::MatrixX2i polygon_edges(int num_vertices, const std::vector<std::vector<int>>& faces) {
  std::vector<std::pair<int, int>> edges;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& face = faces[f];
    for (std::size_t i = 0; i < face.size(); ++i) {
      const int a = face[i], b = face[(i + 1) % face.size()];
      if (a < 0 || b < 0 || a >= num_vertices || b >= num_vertices)
        throw InputError("feature fidelity", 0, "face " + std::to_string(f) + " has a vertex index out of range");
      if (a != b) edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  Eigen::MatrixX2i E(static_cast<Eigen::Index>(edges.size()), 2);
  for (std::size_t e = 0; e < edges.size(); ++e) E.row(static_cast<Eigen::Index>(e)) << edges[e].first, edges[e].second;
  return E;
}

// Sample points along the given input edges, about `spacing` apart (midpoints of equal sub-segments).
std::vector<Eigen::Vector3d> edge_samples(const Mesh& mesh, const std::vector<int>& edges, double spacing) {
  std::vector<Eigen::Vector3d> out;
  for (int e : edges) {
    const Eigen::Vector3d a = mesh.V().row(mesh.E()(e, 0)).transpose(), b = mesh.V().row(mesh.E()(e, 1)).transpose();
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing)));
    for (int i = 0; i < n; ++i) out.push_back(a + ((i + 0.5) / n) * (b - a));
  }
  return out;
}

FeatureFidelityPart summarize(int edges, std::vector<double> d, double covered_within) {
  FeatureFidelityPart p;
  p.edges = edges;
  p.samples = static_cast<int>(d.size());
  if (d.empty()) return p;
  std::sort(d.begin(), d.end());
  double sum = 0;
  int covered = 0;
  for (double x : d) {
    sum += x;
    covered += x <= covered_within;
  }
  const std::size_t n = d.size();
  p.covered_percent = 100.0 * covered / static_cast<double>(n);
  p.mean = sum / static_cast<double>(n);
  p.p95 = d[static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(n))) - 1];  // nearest rank
  p.max = d.back();
  return p;
}

}  // namespace

FeatureFidelity feature_fidelity(const Mesh& reference, const Eigen::MatrixX3d& V,
                                 const std::vector<std::vector<int>>& faces, const FeatureFidelityOptions& options) {
  const Eigen::MatrixX2i E = polygon_edges(static_cast<int>(V.rows()), faces);
  double total = 0;
  for (Eigen::Index e = 0; e < E.rows(); ++e) total += (V.row(E(e, 1)) - V.row(E(e, 0))).norm();
  if (!(total > 0)) throw InputError("feature fidelity", 0, "the output mesh has no edge of positive length");
  FeatureFidelity out;
  out.h = total / static_cast<double>(E.rows());
  const std::vector<int> boundary = options.features.boundaries ? reference.boundary_edges() : std::vector<int>{};
  const auto sharp_edges = [&](FeatureOptions features) {
    features.boundaries = false;
    return feature_constraints(reference, features).feature_edges;
  };
  const std::vector<int> sharp = sharp_edges(options.features), followed = sharp_edges(options.followed);
  const SegmentGrid grid(V, E);
  const auto distances = [&](const std::vector<int>& edges) {
    const std::vector<Eigen::Vector3d> s = edge_samples(reference, edges, options.spacing * out.h);
    std::vector<double> d(s.size());
    tbb::parallel_for(std::size_t{0}, s.size(),
                      [&](std::size_t i) { d[i] = std::sqrt(grid.squared_distance(s[i])) / out.h; });
    return d;
  };
  std::vector<double> db = distances(boundary), ds = distances(sharp), all = db;
  all.insert(all.end(), ds.begin(), ds.end());
  const int n_edges = static_cast<int>(boundary.size() + sharp.size());
  out.total = summarize(n_edges, std::move(all), options.covered_within);
  out.boundary = summarize(static_cast<int>(boundary.size()), std::move(db), options.covered_within);
  out.sharp = summarize(static_cast<int>(sharp.size()), std::move(ds), options.covered_within);
  out.followed = summarize(static_cast<int>(followed.size()), distances(followed), options.covered_within);
  return out;
}

nlohmann::json feature_fidelity_to_json(const FeatureFidelity& f) {
  const auto part = [](const FeatureFidelityPart& p) {
    nlohmann::json j{{"edges", p.edges}, {"samples", p.samples}};
    const bool any = p.samples > 0;
    j["covered_percent"] = any ? nlohmann::json(p.covered_percent) : nlohmann::json();
    j["mean"] = any ? nlohmann::json(p.mean) : nlohmann::json();
    j["p95"] = any ? nlohmann::json(p.p95) : nlohmann::json();
    j["max"] = any ? nlohmann::json(p.max) : nlohmann::json();
    return j;
  };
  return {{"h", f.h},
          {"boundary", part(f.boundary)},
          {"sharp", part(f.sharp)},
          {"followed", part(f.followed)},
          {"total", part(f.total)}};
}

}  // namespace quadcover
