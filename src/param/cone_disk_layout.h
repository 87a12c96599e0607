#pragma once
// A disk around a wrongly wound branch point laid out again in its cone chart (beyond the thesis; issue 14).
// A branch point p held on its lattice point L can come out of the untangling wound a turn short (e.g. π/2 for a
// −1/4 cone, whose angle is 5π/2) with a regular vertex beside it at 4π: every triangle positive, so no untangling
// changes it, and laying out p's ring alone leaves the turn in the rings beyond. But a few rings out the map is
// right again: the boundary ∂D of the k-ring disk D around p sweeps the cone angle Θ_p around L (another sheet of D
// covers L). Then D can be laid out again with the boundary where it is: in the flattened chart w = (z − L)^{2π/Θ_p}
// (z in p's developed chart, param/map_development.h) ∂D is a closed curve around 0. If it is star-shaped around 0,
// D is laid out by Tutte's barycentric layout with ∂D's vertices evenly on the unit circle (p lands near the centre),
// moved so that p is at 0 by a warp that keeps the rim, and carried onto the flattened disk by the radial
// homeomorphism that sends the circle onto ∂D; z = L + w^{Θ_p/2π} then winds Θ_p around p and 2π around every other
// interior vertex. The untangler repairs what the piecewise-linear layout leaves folded, and once every triangle is
// positive the disk is polished inside the injective set (param/untangle.h polish_map): the layout stretches it.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "cover/complex_stiffness.h"
#include "mesh/mesh.h"

namespace quadcover {

inline constexpr int kMaxConeDiskRings = 24;
inline constexpr std::size_t kMaxConeDiskFaces = 4000;

/// Lays out again the smallest disk D of k ≤ kMaxConeDiskRings rings around the branch point p (faces with a vertex
/// within k − 1 rings; at most kMaxConeDiskFaces faces) whose boundary sweeps theta around φ(p) (see above),
/// φ = base − layered_values(u); near a wrongly wound cone the map is stretched, and on a dense mesh the boundary
/// sweeps theta only 7-8 rings out (igea_270k). D must be a topological disk of interior vertices, with no branch
/// point but p and no held component (`fixed`, 2·#V) inside.
/// \return the vertices moved (D's interior but p, ascending; u changed there), or empty (u unchanged) if no k gives
/// such a disk or the layout does not wind theta around p.
/// \pre layers fit mesh, u #V, fixed 2·#V, p a branch point with faces, theta > 0.
std::vector<int> lay_out_cone_disk(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                                   const std::vector<char>& fixed, double theta, int p, Eigen::VectorXcd& u);

}  // namespace quadcover
