#pragma once
// Regions of stable curvature directions and propagation from them (thesis 5.1.2).
#include <Eigen/Core>
#include <vector>

#include "field/curvature_frames.h"
#include "mesh/mesh.h"

namespace quadcover {

/// Stability weights (5.2): ω_t = |κ_max - κ_min| · exp(-½(|θ_e1| + |θ_e2| + |θ_e3|)), θ the curvature (3.4) of
/// the curvature frames with their straightest matching (boundary edges contribute 0).
/// theta  #E. \return #F, >= 0 \pre frames = curvature_frames(mesh, …); theta has #E entries.
Eigen::VectorXd stability_weights(const Mesh& mesh, const CurvatureFrames& frames, const Eigen::VectorXd& theta);

/// Trusted faces: every face in `always` (#F, may be empty: e.g. feature-constrained faces), plus the
/// ceil(fraction·#F) faces of largest weight (ties: lower index), plus, in any connected component that would
/// otherwise have none, its face of largest weight, so that propagation reaches every face.
/// \return #F flags \pre weights has #F entries; always is empty or has #F; 0 <= fraction <= 1.
std::vector<char> select_trusted(const Mesh& mesh, const Eigen::VectorXd& weights, double fraction,
                                 const std::vector<char>& always = {});

/// Breadth-first extension of the trusted frames to all other faces by parallel transport across edges
/// (Levi-Civita, Mesh::edge_transport): an untrusted face takes the transported frame of the face it was first
/// reached from. Sources are visited by decreasing weight, so the most stable frames win ties.
/// X  #F unit frames; trusted  #F flags (at least one per connected component); weights  #F. \return #F
/// \throw NumericalError if some face is not reached (a component without a trusted face).
Eigen::VectorXcd propagate_frames(const Mesh& mesh, const Eigen::VectorXcd& X, const std::vector<char>& trusted,
                                  const Eigen::VectorXd& weights);

}  // namespace quadcover
