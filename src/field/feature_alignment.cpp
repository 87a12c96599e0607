#include "field/feature_alignment.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <utility>

#include "common/union_find.h"
#include "field/crease_loops.h"
#include "mesh/segment_grid.h"
#include "mesh/shape_operator.h"

namespace quadcover {

namespace {

// The chains of sharp edges continuing each other (turning by less than 40° at their common vertex): per sharp edge
// (in `sharp`'s order) its chain's edge count and length.
struct Chains {
  std::vector<int> edges;
  std::vector<double> length;
};

Chains sharp_chains(const Mesh& mesh, const std::vector<int>& sharp) {
  const int ne = mesh.num_edges();
  std::vector<std::vector<int>> at(static_cast<std::size_t>(mesh.num_vertices()));
  for (int e : sharp)
    for (int j = 0; j < 2; ++j) at[static_cast<std::size_t>(mesh.E()(e, j))].push_back(e);
  detail::UnionFind curves(ne);
  const auto away = [&](int e, int v) {  // unit direction of e leaving v
    const int w = mesh.E()(e, 0) == v ? mesh.E()(e, 1) : mesh.E()(e, 0);
    return Eigen::Vector3d((mesh.V().row(w) - mesh.V().row(v)).normalized());
  };
  const double continues = -std::cos(40.0 * std::numbers::pi / 180.0);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const auto& edges = at[static_cast<std::size_t>(v)];
    for (std::size_t i = 0; i < edges.size(); ++i)
      for (std::size_t j = i + 1; j < edges.size(); ++j)
        if (away(edges[i], v).dot(away(edges[j], v)) < continues)
          curves.unite(edges[i], edges[j]);
  }
  std::vector<int> size(static_cast<std::size_t>(ne), 0);
  std::vector<double> length(static_cast<std::size_t>(ne), 0.0);
  for (int e : sharp) {
    ++size[static_cast<std::size_t>(curves.find(e))];
    length[static_cast<std::size_t>(curves.find(e))] += mesh.edge_lengths()[e];
  }
  Chains chains;
  for (int e : sharp) {
    chains.edges.push_back(size[static_cast<std::size_t>(curves.find(e))]);
    chains.length.push_back(length[static_cast<std::size_t>(curves.find(e))]);
  }
  return chains;
}

// Per sharp edge: whether every edge of its faces that is not sharp bends by less than `degrees`.
std::vector<char> crisp_edges(const Mesh& mesh, const Eigen::VectorXd& beta, const std::vector<int>& sharp,
                              double degrees) {
  std::vector<char> is_sharp(static_cast<std::size_t>(mesh.num_edges()), 0);
  for (int e : sharp) is_sharp[static_cast<std::size_t>(e)] = 1;
  const double limit = degrees * std::numbers::pi / 180.0;
  const auto calm = [&](int f) {
    for (int k = 0; k < 3; ++k) {
      const int g = mesh.FE()(f, k);
      if (is_sharp[static_cast<std::size_t>(g)] == 0 && std::abs(beta[g]) >= limit) return false;
    }
    return true;
  };
  std::vector<char> crisp(sharp.size());
  for (std::size_t i = 0; i < sharp.size(); ++i)
    crisp[i] = calm(mesh.EF()(sharp[i], 0)) && calm(mesh.EF()(sharp[i], 1));
  return crisp;
}

// Clears the `candidate` edges that do not lie between two corners of the network of the `kept` and candidate edges
// (those with an end no other edge of it reaches, repeatedly), then those joined to fewer than min_edges candidates.
void keep_between_corners(const Mesh& mesh, const std::vector<int>& sharp, const std::vector<char>& kept,
                          std::vector<char>& candidate, int min_edges) {
  std::vector<int> degree(static_cast<std::size_t>(mesh.num_vertices()), 0);
  const auto in_network = [&](std::size_t i) { return kept[i] != 0 || candidate[i] != 0; };
  const auto end = [&](std::size_t i, int j) { return static_cast<std::size_t>(mesh.E()(sharp[i], j)); };
  for (std::size_t i = 0; i < sharp.size(); ++i)
    if (in_network(i)) ++degree[end(i, 0)], ++degree[end(i, 1)];
  std::vector<std::vector<std::size_t>> at(static_cast<std::size_t>(mesh.num_vertices()));  // candidates per vertex
  for (std::size_t i = 0; i < sharp.size(); ++i)
    if (candidate[i] != 0) at[end(i, 0)].push_back(i), at[end(i, 1)].push_back(i);
  std::vector<std::size_t> loose;  // vertices one network edge reaches
  for (std::size_t v = 0; v < degree.size(); ++v)
    if (degree[v] == 1) loose.push_back(v);
  while (!loose.empty()) {
    const std::size_t v = loose.back();
    loose.pop_back();
    for (const std::size_t i : at[v]) {
      if (candidate[i] == 0 || degree[v] != 1) continue;
      candidate[i] = 0;
      for (int j = 0; j < 2; ++j)
        if (--degree[end(i, j)] == 1) loose.push_back(end(i, j));
    }
  }
  detail::UnionFind network(mesh.num_vertices());
  for (std::size_t i = 0; i < sharp.size(); ++i)
    if (candidate[i] != 0) network.unite(static_cast<int>(end(i, 0)), static_cast<int>(end(i, 1)));
  std::vector<int> size(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (std::size_t i = 0; i < sharp.size(); ++i)
    if (candidate[i] != 0) ++size[static_cast<std::size_t>(network.find(static_cast<int>(end(i, 0))))];
  for (std::size_t i = 0; i < sharp.size(); ++i)
    if (size[static_cast<std::size_t>(network.find(static_cast<int>(end(i, 0))))] < min_edges) candidate[i] = 0;
}

// Keeps the sharp edges on long chains and the crisp ones between corners of their network
// (FeatureOptions::min_curve_edges, crisp_crease_degrees, crisp_min_length); returns how many are kept as crisp.
int keep_feature_curves(const Mesh& mesh, const FeatureOptions& options, const Eigen::VectorXd& beta,
                        std::vector<int>& sharp) {
  const int min_edges = options.min_curve_edges;
  if (min_edges <= 1 || sharp.empty()) return 0;
  const Chains chains = sharp_chains(mesh, sharp);
  std::vector<char> on_chain(sharp.size());
  for (std::size_t i = 0; i < sharp.size(); ++i) on_chain[i] = chains.edges[i] >= min_edges;
  std::vector<char> crisp(sharp.size(), 0);
  if (options.crisp_crease_degrees > 0) {
    crisp = crisp_edges(mesh, beta, sharp, options.crisp_crease_degrees);
    for (std::size_t i = 0; i < sharp.size(); ++i)
      crisp[i] = crisp[i] != 0 && on_chain[i] == 0 && chains.length[i] >= options.crisp_min_length;
    keep_between_corners(mesh, sharp, on_chain, crisp, min_edges);
  }
  std::vector<int> kept;
  for (std::size_t i = 0; i < sharp.size(); ++i)
    if (on_chain[i] != 0 || crisp[i] != 0) kept.push_back(sharp[i]);
  sharp = std::move(kept);
  return static_cast<int>(std::count(crisp.begin(), crisp.end(), 1));
}

// The interior edges lying on the given segments: both ends and the midpoint within a 1e-9 of the mean edge length.
std::vector<int> edges_on_segments(const Mesh& mesh, const std::vector<FeatureSegment>& given) {
  std::vector<int> edges;
  if (given.empty()) return edges;
  Eigen::MatrixX3d ends(2 * given.size(), 3);
  Eigen::MatrixX2i segments(given.size(), 2);
  for (std::size_t s = 0; s < given.size(); ++s) {
    const auto i = static_cast<Eigen::Index>(s);
    ends.row(2 * i) = given[s].a.transpose();
    ends.row(2 * i + 1) = given[s].b.transpose();
    segments.row(i) << static_cast<int>(2 * i), static_cast<int>(2 * i + 1);
  }
  const SegmentGrid grid(ends, segments);
  const double tolerance = 1e-9 * mesh.mean_edge_length();
  const auto on = [&](const Eigen::Vector3d& p) { return grid.squared_distance(p) <= tolerance * tolerance; };
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    const Eigen::Vector3d a = mesh.V().row(mesh.E()(e, 0)).transpose(), b = mesh.V().row(mesh.E()(e, 1)).transpose();
    if (on(a) && on(b) && on(0.5 * (a + b))) edges.push_back(e);
  }
  return edges;
}

// The sharp interior edges: the given ones, or those above the angle on long chains or crisp between corners.
FollowedSharpEdges sharp_edges(const Mesh& mesh, const FeatureOptions& options, const Eigen::VectorXd& beta) {
  FollowedSharpEdges sharp;
  if (options.given) {
    sharp.edges = edges_on_segments(mesh, *options.given);
    return sharp;
  }
  if (options.sharp_angle_degrees <= 0) return sharp;
  const double threshold = options.sharp_angle_degrees * std::numbers::pi / 180.0;
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (!mesh.is_boundary_edge(e) && std::abs(beta[e]) > threshold) sharp.edges.push_back(e);
  sharp.crisp = keep_feature_curves(mesh, options, beta, sharp.edges);
  return sharp;
}

}  // namespace

bool has_sharp_features(const FeatureOptions& options) {
  return options.given ? !options.given->empty() : options.sharp_angle_degrees > 0;
}

std::vector<FeatureSegment> feature_segments(const Mesh& mesh, const std::vector<int>& mesh_vertex_of_input,
                                             const std::vector<std::pair<int, int>>& edges,
                                             RefusedFeatureEdge& refused) {
  using Why = RefusedFeatureEdge::Why;
  refused = {};
  std::vector<std::pair<int, int>> present;
  for (int e = 0; e < mesh.num_edges(); ++e) present.push_back(std::minmax(mesh.E()(e, 0), mesh.E()(e, 1)));
  std::sort(present.begin(), present.end());
  const auto n = static_cast<int>(mesh_vertex_of_input.size());
  const auto mesh_vertex = [&](int v) { return v < n ? mesh_vertex_of_input[static_cast<std::size_t>(v)] : -1; };
  std::vector<FeatureSegment> out;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto [a, b] = edges[i];
    const int ma = mesh_vertex(a), mb = mesh_vertex(b);
    if (ma < 0 || mb < 0) {
      const int v = ma < 0 ? a : b;
      refused = {v < n ? Why::kVertexInNoFace : Why::kNoSuchVertex, static_cast<int>(i), v};
      return out;
    }
    const std::pair<int, int> key = std::minmax(ma, mb);
    if (!std::binary_search(present.begin(), present.end(), key)) {
      refused = {Why::kNotAnEdge, static_cast<int>(i), -1};
      return out;
    }
    out.push_back({mesh.V().row(key.first).transpose(), mesh.V().row(key.second).transpose()});
  }
  return out;
}

FollowedSharpEdges followed_sharp_edges(const Mesh& mesh, const FeatureOptions& options) {
  return sharp_edges(mesh, options, signed_dihedral_angles(mesh));
}

FeatureConstraints feature_constraints(const Mesh& mesh, const FeatureOptions& options) {
  const int nf = mesh.num_faces(), ne = mesh.num_edges();
  const Eigen::VectorXd beta = signed_dihedral_angles(mesh);
  Eigen::VectorXd strength = Eigen::VectorXd::Zero(ne);
  FeatureConstraints out;
  if (options.boundaries)
    for (int e = 0; e < ne; ++e)
      if (mesh.is_boundary_edge(e)) strength[e] = std::numbers::pi;
  out.feature_edges = sharp_edges(mesh, options, beta).edges;
  // A given edge may be flat: it still wins over no feature, and boundaries still win over it.
  for (int e : out.feature_edges) strength[e] = std::max(std::abs(beta[e]), 1e-6);
  out.constrained.assign(static_cast<std::size_t>(nf), 0);
  out.source_edge.assign(static_cast<std::size_t>(nf), -1);
  out.direction = Eigen::VectorXcd::Zero(nf);
  std::vector<unsigned char> freed(static_cast<std::size_t>(nf), 0);
  if (options.free_short_loops_below > 0)
    freed = freed_loop_sides(mesh, closed_crease_loops(mesh, out.feature_edges), options.free_short_loops_below);
  for (int f = 0; f < nf; ++f) {
    int best = -1;
    for (int k = 0; k < 3; ++k) {
      const int e = mesh.FE()(f, k);
      if (strength[e] == 0 || (freed[f] >> k & 1) != 0) continue;
      if (best < 0) {
        best = k;
        continue;
      }
      const int b = mesh.FE()(f, best);
      if (strength[e] > strength[b] || (strength[e] == strength[b] && mesh.edge_lengths()[e] > mesh.edge_lengths()[b]))
        best = k;
    }
    if (best < 0) continue;
    const Complex d = mesh.edge_vector_local(f, best);
    out.constrained[static_cast<std::size_t>(f)] = 1;
    out.source_edge[static_cast<std::size_t>(f)] = mesh.FE()(f, best);
    out.direction[f] = d / std::abs(d);
  }
  return out;
}

}  // namespace quadcover
