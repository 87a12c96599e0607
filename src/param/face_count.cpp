#include "param/face_count.h"

#include <algorithm>
#include <cmath>

namespace quadcover {

double parameter_area(const Mesh& mesh, const Eigen::MatrixX3cd& uv) {
  double a = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Complex e1 = uv(f, 1) - uv(f, 0), e2 = uv(f, 2) - uv(f, 0);
    a += 0.5 * std::abs(e1.real() * e2.imag() - e1.imag() * e2.real());
  }
  return a;
}

namespace {

// True if the segment a-b lies on an integer iso-line of φ (a boundary aligned to the grid cuts no cell).
bool on_one_iso_line(Complex a, Complex b) {
  constexpr double kTol = 1e-6;
  auto same_integer = [](double x, double y) {
    return std::abs(x - std::round(x)) < kTol && std::abs(y - std::round(y)) < kTol && std::round(x) == std::round(y);
  };
  return same_integer(a.real(), b.real()) || same_integer(a.imag(), b.imag());
}

/// Σ |b − a| over the boundary edges a → b of the map for which `counts(a, b)` holds.
template <class Counts>
double boundary_length_where(const Mesh& mesh, const Eigen::MatrixX3cd& uv, Counts counts) {
  double length = 0;
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (!mesh.is_boundary_edge(e)) continue;
    const int side = mesh.EF()(e, 0) >= 0 ? 0 : 1;
    const int f = mesh.EF()(e, side), k = mesh.EF_corner()(e, side);
    const Complex a = uv(f, (k + 1) % 3), b = uv(f, (k + 2) % 3);
    if (counts(a, b)) length += std::abs(b - a);
  }
  return length;
}

}  // namespace

double cut_boundary_length(const Mesh& mesh, const Eigen::MatrixX3cd& uv) {
  return boundary_length_where(mesh, uv, [](Complex a, Complex b) { return !on_one_iso_line(a, b); });
}

double slanted_boundary_length(const Mesh& mesh, const Eigen::MatrixX3cd& uv, double max_turn_radians) {
  const double tolerance = std::sin(max_turn_radians);
  return boundary_length_where(mesh, uv, [tolerance](Complex a, Complex b) {
    const Complex d = b - a;
    return std::min(std::abs(d.real()), std::abs(d.imag())) > tolerance * std::abs(d);
  });
}

double expected_face_count(const Mesh& mesh, const Eigen::MatrixX3cd& uv) {
  return parameter_area(mesh, uv) + 0.5 * cut_boundary_length(mesh, uv);
}

}  // namespace quadcover
