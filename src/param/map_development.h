#pragma once
// The map around a vertex developed into one chart (beyond the thesis; issue 14). A seamless map φ is given per
// face in the face's own chart; across an edge the charts differ by a transition φ_g = i^m φ_f + t, read at a
// shared regular vertex r (m = λ_g(r) − λ_f(r) of the covering's layers, t from φ there). Composing them along a
// walk over the faces around p puts every nearby corner in the chart of p's first fan face, where distances and
// coincidences of points can be read (e.g. two branch points rounded to one lattice point a few edges apart).
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "cover/complex_stiffness.h"
#include "mesh/mesh.h"

namespace quadcover {

/// The transition φ_g = i^m φ_f + t from face f to the adjacent face g, read at a regular vertex r they share
/// (m = λ_g(r) − λ_f(r), t from φ there, φ = base − layered_values(mesh, layers, u)).
/// \pre layers fit mesh, u #V, r a regular vertex of both f and g.
std::pair<int, Complex> face_transition(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                                        const Eigen::VectorXcd& u, int f, int g, int r);

/// Per corner of the faces touching the vertices within rings − 1 rings of p that a breadth-first walk over edges
/// with a regular end reaches (from p's first fan face, neighbours in face-edge order): its vertex and φ there in
/// the chart of p's first fan face, φ = base − layered_values(mesh, layers, u). A vertex can appear with several
/// positions (walks around different branch points). \pre layers fit mesh, u #V, p has faces, rings >= 1.
/// Deterministic.
std::vector<std::pair<int, Complex>> developed_around(const Mesh& mesh, const VertexLayers& layers,
                                                      const Eigen::MatrixX3cd& base, const Eigen::VectorXcd& u, int p,
                                                      int rings);

}  // namespace quadcover
