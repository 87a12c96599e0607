#include "param/density.h"

#include <algorithm>
#include <cmath>

#include "common/errors.h"
#include "field/indices.h"

namespace quadcover {

double target_edge_length(const Mesh& mesh, const DensityOptions& options, int branch_points) {
  if (options.edge_length < 0 || options.target_quads < 0)
    throw InputError("", 0, "the edge length and the number of quads must be positive");
  if (options.edge_length > 0) return options.edge_length;
  if (options.target_quads > 0) return std::sqrt(mesh.total_area() / options.target_quads);
  double h = options.default_edge_factor * mesh.mean_edge_length();
  if (options.min_quads_per_branch_point > 0 && branch_points > 0)
    h = std::min(h, std::sqrt(mesh.total_area() / (options.min_quads_per_branch_point * branch_points)));
  return h;
}

void fix_default_density(const Mesh& mesh, const FrameField& field, DensityOptions& options) {
  if (options.edge_length > 0 || options.target_quads > 0) return;
  options.edge_length = target_edge_length(mesh, options, static_cast<int>(branch_points(mesh, field).size()));
}

}  // namespace quadcover
