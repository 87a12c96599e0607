#pragma once
// Complex Hermitian stiffness matrices of the 4-sheeted covering M̃ (thesis 3.2.3) and the complex curl* of a
// frame field (3.3). Complex functions ū on M stand for symmetric functions ũ on M̃: ū_i = ũ_{4i} + i ũ_{4i+1}.
#include <Eigen/SparseCore>

#include "field/frame_field.h"

namespace quadcover {

/// 𝔏̄* (3.8): #E by #E Hermitian, (i,j) = i^l 𝔏*_ij where ẽ_i^l ~ ẽ_j^0 under the matching, (i,i) = 𝔏*_ii.
/// Its sparsity pattern equals that of 𝔏* for every matching (zero-valued entries are stored explicitly).
Eigen::SparseMatrix<Complex> complex_nonconforming_stiffness(const Mesh& mesh, const Eigen::VectorXi& matching);

/// 𝔏̄: #V by #V Hermitian, (p,q) = i^l 𝔏_pq with ṽ_p^l ~ ṽ_q^0; rows and columns of branch points are zero
/// except for a unit diagonal (so the matrix stays invertible; the value there is pinned to 0).
Eigen::SparseMatrix<Complex> complex_conforming_stiffness(const Mesh& mesh, const Eigen::VectorXi& matching);

/// curl* Z(e) (3.3) of the frame field Z = X + iY with its matching, #E complex.
Eigen::VectorXcd complex_curl_star(const Mesh& mesh, const FrameField& field);

}  // namespace quadcover
