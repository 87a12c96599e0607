#pragma once
// Matchings and frame-field curvature (thesis 1.4, 3.1.2, (3.4), (5.1)). Sign conventions: field/frame_field.h.
#include <Eigen/Core>

#include "field/frame_field.h"
#include "mesh/mesh.h"

namespace quadcover {

/// Intrinsic angle ∠_e = arg(X_t / (ρ_e X_s)) ∈ (-π, π] from X_s to X_t across interior edge e, measured after
/// unfolding s and t into a plane (Mesh::edge_transport). 0 on boundary edges.
/// X  #F complex, face basis. \return #E \pre X has #F entries.
Eigen::VectorXd intrinsic_angles(const Mesh& mesh, const Eigen::VectorXcd& X);

/// Straightest matching (5.1): m_e = round(2∠_e/π), so that |θ_e| <= π/4. 0 on boundary edges. \return #E
/// \pre X has #F entries.
Eigen::VectorXi straightest_matching(const Mesh& mesh, const Eigen::VectorXcd& X);

/// Curvature (3.4) of a frame field: θ_e = arg(X_t / (i^{m_e} ρ_e X_s)) ∈ (-π, π] with the orthogonalized frames
/// (= ∠_e - (π/2) m_e whenever that lies in (-π, π]; see field/frame_field.h). 0 on boundary edges. \return #E
/// \pre field belongs to mesh (X, Y #F, matching #E).
Eigen::VectorXd field_curvature(const Mesh& mesh, const FrameField& field);

/// x wrapped to (-π, π]. \pre x is finite.
double wrap_angle(double x);

/// Cross field with first vectors X and the straightest matching (5.1). \pre X has #F entries.
FrameField cross_field_with_straightest_matching(const Mesh& mesh, const Eigen::VectorXcd& X);

/// Smoothing energy of the MIQ type used in thesis 5.2: E_S = Σ_e ω_e θ_e², ω_e = ‖e‖²/A_e, A_e = ⅓(A_s + A_t).
/// \pre field belongs to mesh.
double smoothing_energy(const Mesh& mesh, const FrameField& field);
/// The edge weights ω_e of E_S (0 on boundary edges). \return #E \pre none
Eigen::VectorXd smoothing_edge_weights(const Mesh& mesh);

}  // namespace quadcover
