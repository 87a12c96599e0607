#pragma once
// Checks shared by the tests of the final solve (stiffening, relaxation, parameterize).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "param/seams.h"

// ½‖X̃ − ∇φ̃‖² on the covering (= Σ_t A_t |·|² of both frame vectors on M), X̃ the scaled, gauged frames: the
// total that E_D + E_H (+ the prices E_R, E_K of relaxation and stiffening) must add up to (6.1.1).
#include "field/frame_field.h"
#include "mesh/mesh.h"
#include "param/disk_functions.h"
#include "param/parameterization.h"

namespace quadcover::testing {

inline double map_field_energy(const Mesh& mesh, const FrameField& field, const Parameterization& P) {
  double s = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto [g0, g1] = face_gradient(mesh, P.uv, f);
    const auto [x, y] = turn_frame(field.X[f], field.Y[f], P.face_rotation[f]);
    s += mesh.face_areas()[f] * (std::norm(P.scale * x - g0) + std::norm(P.scale * y - g1));
  }
  return s;
}

// Per-corner uv of the map (x, y) ↦ a x + b y (complex a, b) on a flat mesh.
inline Eigen::MatrixX3cd linear_map(const Mesh& mesh, Complex a, Complex b) {
  Eigen::MatrixX3cd uv(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d p = mesh.V().row(mesh.F()(f, c));
      uv(f, c) = a * p.x() + b * p.y();
    }
  return uv;
}

// The map is seamless, its branch points (but the reported unfixed even ones) lie on integer points, and every
// enforced curve lies on its integer iso-line, all to 1e-9 of the parameter extent.
inline void expect_seamless_grid_map(const Mesh& mesh, const Parameterization& P) {
  const SeamReport seams = measure_seams(mesh, P.uv);
  EXPECT_TRUE(seams.seamless) << seams.max_transition_error;
  const double tol = 1e-9 * seams.parameter_extent;
  for (const BranchPoint& bp : P.branch_points) {
    if (std::count(P.diagnostics.unfixed_even_branch_points.begin(), P.diagnostics.unfixed_even_branch_points.end(), bp.vertex)) continue;
    for (const auto& fc : mesh.fan(bp.vertex)) {
      const Complex z = P.uv(fc.face, fc.corner);
      ASSERT_LT(std::abs(z - Complex(std::round(z.real()), std::round(z.imag()))), tol) << bp.vertex;
    }
  }
  for (const auto& curve : P.aligned_curves)
    if (curve.enforced) {
      EXPECT_LT(curve.max_deviation, tol) << curve.value;
    }
}

}  // namespace quadcover::testing
