#include "param/density.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "common/errors.h"
#include "field/indices.h"

namespace quadcover {

LoopResolution loop_resolution(const Mesh& mesh, const DensityOptions& options, double h) {
  LoopResolution r;
  r.edge_length = h;
  if (options.min_loop_grid_units <= 0) return r;
  const double finest = std::max(h / std::sqrt(options.max_loop_quads_factor),
                                 std::sqrt(mesh.total_area() / std::max(mesh.num_faces(), 1)));
  double resolving = h;
  const auto consider = [&](int loop, bool rim, int lowest_vertex, double length) {
    const double needed = length / options.min_loop_grid_units;
    if (needed >= resolving || needed < finest) return;
    resolving = needed;
    r.loop = loop;
    r.rim = rim;
    r.lowest_vertex = lowest_vertex;
    r.length = length;
  };
  const auto& loops = mesh.boundary_loops();
  for (std::size_t l = 0; l < loops.size(); ++l) {
    double length = 0;
    for (const int e : mesh.boundary_loop_edges()[l]) length += mesh.edge_lengths()[e];
    consider(static_cast<int>(l), false, *std::min_element(loops[l].begin(), loops[l].end()), length);
  }
  for (std::size_t l = 0; l < options.hole_rims.size(); ++l)
    consider(static_cast<int>(l), true, options.hole_rims[l].lowest_vertex, options.hole_rims[l].length);
  r.quads_factor = (h / resolving) * (h / resolving);
  return r;
}

double target_edge_length(const Mesh& mesh, const DensityOptions& options, int branch_points) {
  if (options.edge_length < 0 || options.target_quads < 0)
    throw InputError("", 0, "the edge length and the number of quads must be positive");
  if (options.edge_length > 0) return options.edge_length;
  if (options.target_quads > 0) return std::sqrt(mesh.total_area() / options.target_quads);
  double h = options.default_edge_factor * mesh.mean_edge_length();
  if (options.min_quads_per_branch_point > 0 && branch_points > 0)
    h = std::min(h, std::sqrt(mesh.total_area() / (options.min_quads_per_branch_point * branch_points)));
  return h / std::sqrt(loop_resolution(mesh, options, h).quads_factor);
}

LoopResolution fix_default_density(const Mesh& mesh, const FrameField& field, DensityOptions& options) {
  if (options.edge_length > 0 || options.target_quads > 0) return {};
  DensityOptions unraised = options;
  unraised.min_loop_grid_units = 0;
  const double h = target_edge_length(mesh, unraised, static_cast<int>(branch_points(mesh, field).size()));
  const LoopResolution r = loop_resolution(mesh, options, h);
  options.edge_length = h / std::sqrt(r.quads_factor);  // = target_edge_length(mesh, options, …)
  return r;
}

namespace {

/// Per component of `mesh` (its own numbering), its place in the order of the components' lowest vertex numbers: the
/// order of DensityOptions::component_density, which the refinements keep (their new vertices come after the input's).
std::vector<int> rank_by_lowest_vertex(const Mesh& mesh) {
  const int nc = mesh.num_components();
  std::vector<int> lowest(static_cast<std::size_t>(nc), mesh.num_vertices()), order(static_cast<std::size_t>(nc));
  for (int v = 0; v < mesh.num_vertices(); ++v)
    lowest[mesh.vertex_component()[v]] = std::min(lowest[mesh.vertex_component()[v]], v);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lowest[a] < lowest[b]; });
  std::vector<int> rank(static_cast<std::size_t>(nc));
  for (int i = 0; i < nc; ++i) rank[order[i]] = i;
  return rank;
}

}  // namespace

bool fix_component_density(const Mesh& mesh, const FrameField& field, double h, DensityOptions& options) {
  options.component_density.clear();
  const int nc = mesh.num_components();
  if (nc < 2 || options.min_quads_per_branch_point <= 0) return false;
  const std::vector<int> rank = rank_by_lowest_vertex(mesh);
  std::vector<double> area(static_cast<std::size_t>(nc), 0.0), branch(static_cast<std::size_t>(nc), 0.0);
  for (int f = 0; f < mesh.num_faces(); ++f) area[rank[mesh.face_component()[f]]] += mesh.face_areas()[f];
  for (const BranchPoint& bp : branch_points(mesh, field)) branch[rank[mesh.vertex_component()[bp.vertex]]] += 1;
  std::vector<int> faces(static_cast<std::size_t>(nc), 0);
  for (int c = 0; c < nc; ++c) faces[rank[c]] = mesh.components()[c].faces;
  std::vector<double> rho(static_cast<std::size_t>(nc), 1.0);
  bool finer = false;
  for (int c = 0; c < nc; ++c) {
    if (branch[c] == 0 || !(area[c] > 0)) continue;
    const double wanted = std::sqrt(options.min_quads_per_branch_point * branch[c] / area[c]) * h;
    const double one_per_triangle = std::sqrt(faces[c] / area[c]) * h;
    const double factor = std::min(wanted, one_per_triangle);
    if (factor > 1.0 + 1e-9) rho[c] = factor, finer = true;  // not for round-off where one h suits
  }
  if (finer) options.component_density = std::move(rho);
  return finer;
}

namespace {

/// Per element, the density factor of the component `element_component` gives it (1 when component_density is empty).
Eigen::VectorXd density_of(const Mesh& mesh, const Eigen::VectorXi& element_component,
                           const std::vector<double>& component_density) {
  Eigen::VectorXd rho = Eigen::VectorXd::Ones(element_component.size());
  if (static_cast<int>(component_density.size()) != mesh.num_components()) return rho;
  const std::vector<int> rank = rank_by_lowest_vertex(mesh);
  for (Eigen::Index i = 0; i < element_component.size(); ++i) rho[i] = component_density[rank[element_component[i]]];
  return rho;
}

}  // namespace

Eigen::VectorXd face_density(const Mesh& mesh, const std::vector<double>& component_density) {
  return density_of(mesh, mesh.face_component(), component_density);
}

Eigen::VectorXd vertex_density(const Mesh& mesh, const std::vector<double>& component_density) {
  return density_of(mesh, mesh.vertex_component(), component_density);
}

}  // namespace quadcover
