#pragma once
// The explicit 4-sheeted branched covering M̃ of a matching (thesis 3.2.2): four copies t̃^l of every face, glued
// across every interior edge e (s = EF(e,0), t = EF(e,1)) as t̃_s^k ~ t̃_t^{k - m_e} (the thesis's m_st is our -m_e),
// and one vertex per cycle of faces around each vertex. Reference implementation, not used by the product: the
// product works with the complex Hermitian operators of cover/complex_stiffness.h on M itself, and
// tests/cover/covering_test.cpp checks them against this covering (𝔏̃* of (3.7) against 𝔏̄*, Lemma 3.5's genus).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "field/frame_field.h"

namespace quadcover {

struct Covering {
  /// #4F by 3: vertices of covering face 4f + l (layer l of face f), corners in the order of F(f, ·).
  Eigen::MatrixX3i F;
  /// #4F by 3: covering edge 4e + r of face edge k of 4f + l; r is the edge layer of (3.5): the layer of the
  /// adjoining copy of the reference face min(EF(e,0), EF(e,1)).
  Eigen::MatrixX3i FE;
  /// Per covering vertex: the base vertex and the layer of (3.2.2) (the layer of the lowest-index base face in its
  /// face cycle). Branch points have 1 (odd) or 2 (even) covering vertices, others 4.
  std::vector<int> base_vertex;
  std::vector<int> layer;
  int num_vertices() const { return static_cast<int>(base_vertex.size()); }  ///< \pre none
  int num_faces() const { return static_cast<int>(F.rows()); }  ///< \pre none
  int num_edges = 0;  ///< 4·#E
  /// Covering face -> connected component (faces joined across covering edges).
  Eigen::VectorXi face_component;
  int num_components = 0;
  /// Per component: χ = v - e + f and the number of boundary loops.
  std::vector<int> euler_characteristic;
  std::vector<int> boundary_loops;
  /// Genus per component from χ = 2 - 2g - b. \pre none
  std::vector<int> genus() const;
};

/// Builds M̃ for the matching (#E). \pre mesh is valid. \throw InputError if the matching has the wrong size.
Covering build_covering(const Mesh& mesh, const Eigen::VectorXi& matching);

/// Positions of the covering vertices (those of their base vertices) for drawing: #Ṽ by 3.
/// \pre covering = build_covering(mesh, …).
Eigen::MatrixX3d covering_positions(const Mesh& mesh, const Covering& covering);

/// The real nonconforming stiffness 𝔏̃* (3.7) of M̃, #4E by #4E, assembled face by face on the covering.
/// \pre covering = build_covering(mesh, …).
Eigen::SparseMatrix<double> covering_nonconforming_stiffness(const Mesh& mesh, const Covering& covering);

/// Lemma 3.5 (4) with Riemann–Hurwitz: χ(M̃) = 4χ(M) - 3 b_odd - 2 b_even; for b_odd > 0, M̃ is connected of genus
/// 4g + b_even + (3/2) b_odd - 3 (the thesis prints ½ b_even; Riemann–Hurwitz and its own count 2g̃ - h_sym =
/// 4g + b_odd - 2 need b_even). Closed connected M only. \return the expected genus of connected M̃.
/// \pre b_even, b_odd >= 0 counts of a closed connected mesh (b_odd even).
int expected_covering_genus(int genus, int b_even, int b_odd);

}  // namespace quadcover
