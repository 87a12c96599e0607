#pragma once
// Functions on the cut disk of a CoverCut (thesis 1.2.5, 4.2.1): integration of curl*-free frame fields (1.12),
// the transitions φ_t = i^{k_e} φ_s + c_e they have across the cut, the linear relations between the translations
// (the composition of the transitions around every vertex off B is the identity), and functions with prescribed
// jumps (the potentials of the Σ̃ fields (1.13) on the covering).
#include <Eigen/Core>
#include <utility>

#include "param/cover_cut.h"
#include "param/cut_fans.h"

namespace quadcover {

/// A frame field as #F by 2 tangent vectors: column 0 the X-part (layer 0), column 1 the Y-part (layer 1).
using FramePairs = Eigen::MatrixX2cd;

/// ⟨w, Z⟩ = ⟨w, X⟩ + i⟨w, Y⟩ for a tangent vector w (frame-complex result). \pre none
inline Complex frame_dot(Complex w, Complex X, Complex Y) {
  return {std::real(std::conj(w) * X), std::real(std::conj(w) * Y)};
}

/// The value x in the chart of face cr.from carried into the chart of cr.to: the transition of cr.edge when it is
/// cut, x itself otherwise. \pre cut = build_cover_cut(mesh, …); c has #E entries; cr.edge lies between its faces.
Complex carry_across(const Mesh& mesh, const CoverCut& cut, const Eigen::VectorXcd& c, const FanCrossing& cr,
                     Complex x);
/// The quarter-turn power carry_across applies: ±k_e across a cut edge, 0 elsewhere. \pre as carry_across.
int crossing_rotation(const Mesh& mesh, const CoverCut& cut, const FanCrossing& cr);

/// Integrates a curl*-free frame field over the cut disk (1.12), u_q = u_p + ⟨e, Z_t⟩, with value 0 at the first
/// corner of each disk. \return per cut-vertex (CutMesh numbering) complex values.
/// \pre cut = build_cover_cut(mesh, …); Z is #F by 2. \throw only std::bad_alloc.
Eigen::VectorXcd integrate_on_disk(const Mesh& mesh, const CoverCut& cut, const FramePairs& Z);

/// Per-corner values (#F by 3) of a function given per cut-vertex. \pre values has cut.disk.num_vertices() entries.
Eigen::MatrixX3cd corner_values(const CoverCut& cut, const Eigen::VectorXcd& values);

/// Gradient per face of a frame-complex function given per corner: (∇Re φ, ∇Im φ), ∇φ_c = J e_c / 2A.
/// \pre phi is #F by 3.
FramePairs corner_gradient(const Mesh& mesh, const Eigen::MatrixX3cd& phi);
/// The same on one face f: (∇Re φ, ∇Im φ). \pre phi is #F by 3; 0 <= f < #F.
std::pair<Complex, Complex> face_gradient(const Mesh& mesh, const Eigen::MatrixX3cd& phi, int f);

/// Translations c_e (#E, 0 off the cut) of a disk function across the cut edges, averaged over the two endpoints;
/// `mismatch` (if given) receives the largest difference between the two endpoint estimates.
/// \pre cut = build_cover_cut(mesh, …); phi is #F by 3.
Eigen::VectorXcd cut_translations(const Mesh& mesh, const CoverCut& cut, const Eigen::MatrixX3cd& phi,
                                  double* mismatch = nullptr);

/// Completes translations given on the path edges (leftover edges e_j) to all cut edges so that the transitions
/// compose to the identity around every vertex off B (processed from the leaves of the shortest-path forest to the
/// roots). Entries of c on tree cut edges are overwritten. \pre c has #E entries. \throw only std::bad_alloc.
void complete_translations(const Mesh& mesh, const CoverCut& cut, Eigen::VectorXcd& c);
/// The same with the cut's fans made once (param/cut_fans.h). \pre fans = cut_fans(mesh, cut); c has #E entries.
void complete_translations(const Mesh& mesh, const CoverCut& cut, const CutFans& fans, Eigen::VectorXcd& c);

/// The same relations over GF(2) for lattice parities: bit j of edge e is the parity of the coefficient of path j
/// in c_e (i ≡ 1 mod 1+i). \return per edge a bitset of num_paths bits (words of 64).
/// \pre cut = build_cover_cut(mesh, …).
std::vector<std::vector<std::uint64_t>> path_parities(const Mesh& mesh, const CoverCut& cut);

/// The function with jumps c across the cut (a potential of Σ̃_c): per corner values, 0 at vertices off the cut; at
/// a branch point the value is the fixed point c/(1 - i^K) of the composed transition, elsewhere on the cut the first
/// wedge of the fan has value 0. \pre cut = build_cover_cut(mesh, …); c has #E entries.
Eigen::MatrixX3cd jump_function(const Mesh& mesh, const CoverCut& cut, const Eigen::VectorXcd& c);
/// The same with the cut's fans made once. \pre fans = cut_fans(mesh, cut); c has #E entries.
Eigen::MatrixX3cd jump_function(const Mesh& mesh, const CoverCut& cut, const CutFans& fans, const Eigen::VectorXcd& c);
/// Whether c is non-zero on a cut edge around fans.vertices[k]: only then is the jump function non-zero in its fan.
/// \pre fans = cut_fans(mesh, cut); c has #E entries; 0 <= k < fans.vertices.size().
bool moves_fan(const CoverCut& cut, const CutFans& fans, const Eigen::VectorXcd& c, int k);
/// Writes the jump function's values at the corners of fans.vertices[k] into sigma (#F by 3). \pre as moves_fan.
void write_fan_jump(const Mesh& mesh, const CoverCut& cut, const CutFans& fans, const Eigen::VectorXcd& c, int k,
                    Eigen::MatrixX3cd& sigma);

/// Composition of the transitions around vertex v (counter-clockwise, from its first fan face): the rotation power
/// K and translation D of z ↦ i^K z + D. \pre cut = build_cover_cut(mesh, …); c has #E entries; 0 <= v < #V.
std::pair<int, Complex> transition_around(const Mesh& mesh, const CoverCut& cut, const Eigen::VectorXcd& c, int v);

/// φ(v) of a branch point v in the chart of its first fan face (fan_crossings(v).front().from): the fixed point
/// D / (1 − i^K) of transition_around(v) with translations T (0 where K = 0). \pre as transition_around.
Complex branch_point_image(const Mesh& mesh, const CoverCut& cut, const Eigen::VectorXcd& T, int v);

}  // namespace quadcover
