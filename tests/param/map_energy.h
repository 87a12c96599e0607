#pragma once
// ½‖X̃ − ∇φ̃‖² on the covering (= Σ_t A_t |·|² of both frame vectors on M), X̃ the scaled, gauged frames: the
// total that E_D + E_H (+ the prices E_R, E_S of relaxation and stiffening) must add up to (6.1.1).
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

}  // namespace quadcover::testing
