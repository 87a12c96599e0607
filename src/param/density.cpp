#include "param/density.h"

#include <algorithm>
#include <cmath>

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
  const auto& loops = mesh.boundary_loops();
  for (std::size_t l = 0; l < loops.size(); ++l) {
    double length = 0;
    for (const int e : mesh.boundary_loop_edges()[l]) length += mesh.edge_lengths()[e];
    const double needed = length / options.min_loop_grid_units;
    if (needed < resolving && needed >= finest) {
      resolving = needed;
      r.loop = static_cast<int>(l);
      r.lowest_vertex = *std::min_element(loops[l].begin(), loops[l].end());
      r.length = length;
    }
  }
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

}  // namespace quadcover
