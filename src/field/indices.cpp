#include "field/indices.h"

#include <cmath>
#include <numbers>
#include <string>

#include "common/errors.h"
#include "field/matching.h"

namespace quadcover {

namespace {

// Calls visit(e, sign) for each edge crossed when walking counter-clockwise through the fan of interior vertex v,
// sign = +1 if the walk crosses e from EF(e,0) to EF(e,1).
template <class Visit>
void for_each_loop_edge(const Mesh& mesh, int v, Visit&& visit) {
  for (const auto& c : mesh.fan(v)) {
    const int e = mesh.FE()(c.face, (c.corner + 1) % 3);  // edge {v, corner+2}: the next face ccw lies across it
    visit(e, mesh.EF()(e, 0) == c.face ? 1 : -1);
  }
}

// (2/π)·s rounded, checking that s is a multiple of π/2.
int quarters(double s, int v) {
  const double q = 2.0 * s / std::numbers::pi;
  const double r = std::round(q);
  if (!(std::abs(q - r) < 1e-6))
    throw NumericalError("field index", "vertex " + std::to_string(v) + ": angle sum " + std::to_string(s) +
                                            " is not a multiple of π/2 (invalid frames)");
  return static_cast<int>(r);
}

// Per interior vertex: (angle defect + Σ ±angle_e around it) in quarter turns (0 at boundary vertices).
Eigen::VectorXi loop_quarters(const Mesh& mesh, const Eigen::VectorXd& angle) {
  Eigen::VectorXi q = Eigen::VectorXi::Zero(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (mesh.is_boundary_vertex(v)) continue;
    double sum = mesh.angle_defect()[v];
    for_each_loop_edge(mesh, v, [&](int e, int sign) { sum += sign * angle[e]; });
    q[v] = quarters(sum, v);
  }
  return q;
}

}  // namespace

Eigen::VectorXi matching_quarter_index(const Mesh& mesh, const Eigen::VectorXi& matching) {
  Eigen::VectorXi q = Eigen::VectorXi::Zero(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (mesh.is_boundary_vertex(v)) continue;
    int sum = 0;
    for_each_loop_edge(mesh, v, [&](int e, int sign) { sum += sign * matching[e]; });
    q[v] = -sum;
  }
  return q;
}

Eigen::VectorXi cross_field_quarter_index(const Mesh& mesh, const FrameField& field) {
  return loop_quarters(mesh, field_curvature(mesh, field));  // Def. 3.3
}

Eigen::VectorXi vector_field_index(const Mesh& mesh, const Eigen::VectorXcd& X) {
  const Eigen::VectorXi quarter = loop_quarters(mesh, intrinsic_angles(mesh, X));
  Eigen::VectorXi ind = Eigen::VectorXi::Zero(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const int q = quarter[v];  // Def. 1.18: a multiple of 2π
    if (q % 4 != 0)
      throw NumericalError("field index",
                           "vertex " + std::to_string(v) + ": vector field angle sum is not a multiple of 2π");
    ind[v] = q / 4;
  }
  return ind;
}

std::vector<BranchPoint> branch_points(const Mesh& mesh, const FrameField& field) {
  const Eigen::VectorXi q = cross_field_quarter_index(mesh, field);
  std::vector<BranchPoint> out;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (q[v] % 4 != 0) out.push_back({v, q[v]});
  return out;
}

Eigen::VectorXi quarter_index_of(int num_vertices, const std::vector<BranchPoint>& points) {
  Eigen::VectorXi q = Eigen::VectorXi::Zero(num_vertices);
  for (const BranchPoint& b : points) q[b.vertex] = b.quarter_index;
  return q;
}

}  // namespace quadcover
