#pragma once
// Complex Hermitian stiffness matrices of the 4-sheeted covering M̃ (thesis 3.2.3) and the complex curl* of a
// frame field (3.3). Complex functions ū on M stand for symmetric functions ũ on M̃: ū_i = ũ_{4i} + i ũ_{4i+1}.
//
// Gauge (how a complex value is read in a face). The "frame-complex" unit i of these functions is NOT the J of
// tangent vectors: a frame-complex number w = w⁰ + i w¹ carries the values of layers 0 and 1 (the X- and Y-parts).
// Across interior edge e (s = EF(e,0) -> t = EF(e,1)) the covering glues layer k of s to layer k - m_e of t
// ((3.5) with the thesis's m_st = -m_e), so a covering function reads w_t = i^{-m_e} w_s.
//  - An edge value ū_e is stored in the gauge of its reference face r(e) = min(EF(e,0), EF(e,1)) (the triangle
//    with the smaller index, as in (3.5)); in the other face it reads i^{μ} ū_e, μ = edge_layers()(f, k).
//  - A vertex value ū_p is stored in the gauge of the lowest-index face around p (thesis 3.2.2); in face f it reads
//    i^{λ} ū_p, λ = vertex_layers()(f, corner). Branch points (Σ matching around p ≠ 0 mod 4) have no gauge.
#include <Eigen/SparseCore>

#include "field/frame_field.h"

namespace quadcover {

/// #F by 3: μ in 0..3 such that edge function ū (reference-face gauge) reads i^μ ū_e on face f's edge k.
/// \throw InputError if matching does not have #E entries.
Eigen::MatrixX3i edge_layers(const Mesh& mesh, const Eigen::VectorXi& matching);

/// Per-corner layers of vertex functions and the branch-point flags.
struct VertexLayers {
  Eigen::MatrixX3i layer;  ///< #F by 3: λ in 0..3, value i^λ ū_p at corner (f, k) (0 at branch points)
  Eigen::VectorXi branch;  ///< #V: 1 iff p is an interior vertex with Σ m_e around p ≠ 0 mod 4
};
/// \throw InputError if matching does not have #E entries.
VertexLayers vertex_layers(const Mesh& mesh, const Eigen::VectorXi& matching);
/// The value i^λ u_p of a vertex function at corner (f, a) of p, with u_p given (0 at a branch point). \pre layers fit
/// the mesh, f and a a corner of p.
inline Complex layered_value(const VertexLayers& layers, int f, int a, int p, Complex u_p) {
  return layers.branch[p] ? Complex(0) : ipow(layers.layer(f, a)) * u_p;
}
/// Per-corner values i^λ u_p of a vertex function u (0 at branch points): the covering function ũ of u on M.
/// \pre layers fit mesh, u has #V entries.
Eigen::MatrixX3cd layered_values(const Mesh& mesh, const VertexLayers& layers, const Eigen::VectorXcd& u);

/// 𝔏̄* (3.8): #E by #E Hermitian, (i,j) = i^l 𝔏*_ij where ẽ_i^l ~ ẽ_j^0 under the matching, (i,i) = 𝔏*_ii.
/// Its sparsity pattern equals that of 𝔏* for every matching (zero-valued entries are stored explicitly).
/// ūᴴ 𝔏̄* ū = ½ ũᵀ 𝔏̃* ũ (3.9) for the symmetric covering function ũ of ū.
/// \throw InputError if matching does not have #E entries.
Eigen::SparseMatrix<Complex> complex_nonconforming_stiffness(const Mesh& mesh, const Eigen::VectorXi& matching);

/// 𝔏̄: #V by #V Hermitian, (p,q) = i^l 𝔏_pq with ṽ_p^l ~ ṽ_q^0; rows and columns of branch points are zero
/// except for a unit diagonal (so the matrix stays invertible; the value there is pinned to 0). Its sparsity
/// pattern is that of 𝔏 for every matching (the zeros of branch points are stored explicitly).
/// `face_weights` (#F, optional): face f contributes w_f ∫_f ⟨∇φ_p, ∇φ_q⟩ (the weighted Dirichlet energy).
/// \throw InputError if matching does not have #E entries or face_weights is neither empty nor #F.
Eigen::SparseMatrix<Complex> complex_conforming_stiffness(const Mesh& mesh, const Eigen::VectorXi& matching,
                                                          const Eigen::VectorXd& face_weights = {});

/// curl* Z(e) (3.3) of the frame field Z = X + iY with its matching, #E complex, in the reference gauge of e:
/// with e oriented positively in s = EF(e,0), curl* Z(e) = ⟨Z_t, e⟩ - ⟨i^{-m_e} Z_s, e⟩ read in r(e)'s gauge
/// (⟨Z, e⟩ = ⟨X, e⟩ + i⟨Y, e⟩). It is the sign for which 𝔏̄* v = -curl* Z is the normal equation of
/// min_v ‖Z - J∇v‖² on the covering (the co-potential of the curl part, (2.1) on M̃); boundary terms vanish.
/// \throw InputError if the field does not have #F frames or its matching #E entries.
Eigen::VectorXcd complex_curl_star(const Mesh& mesh, const FrameField& field);

}  // namespace quadcover
