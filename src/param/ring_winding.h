#pragma once
// The winding of the map around a vertex (beyond the thesis; issue 14). A seamless map φ sends the fan of an interior
// vertex p to a fan of triangles around φ(p) whose signed corner angles at p add up to Θ_p; the transitions around p
// compose to a rotation i^{-k} (Def. 3.2), so Θ_p ≡ 2π(1 − k/4) mod 2π, but only the frame field's cross-field index
// k_p (Def. 3.3, field/indices.h) says which multiple: an immersion has Θ_p = 2π − k_p·π/2 exactly (the cone angle
// of a branch point of index k_p/4). A ring that winds one turn too few or too many around φ(p) (a "fake" cone) is
// a topological defect of the map near p, not a local fold: while no neighbour passes over φ(p), Θ_p cannot change.
// At a branch point, held on its lattice point by the seamless subspace, no untangling inside the subspace (and no
// edge split, which keeps the ring's winding) removes it; the triangle that compensates the missing turn stays
// flipped (Σ_p (2π − Θ_p) = 2πχ + 2π·#{flipped triangles} on a closed surface, Gauss-Bonnet for signed angles).
// rewind_rings() lays the ring of such a vertex out again in the subspace with the right winding: the ring
// vertices keep their distance from φ(p) and get the angles of the 3D fan scaled to Θ_p; the untangler then
// repairs the faces beyond the ring, where the winding is no longer in the way.
#include <Eigen/Core>
#include <vector>

#include "common/progress.h"
#include "cover/complex_stiffness.h"
#include "mesh/mesh.h"
#include "param/untangle.h"

namespace quadcover {

/// φ at corner c of face f: base(f, c) − i^λ u_p with λ = layers.layer(f, c) (base(f, c) at branch points).
/// \pre layers fit mesh, u #V.
Complex corner_value(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                     const Eigen::VectorXcd& u, int f, int c);

/// Θ_p: the signed angle sum of φ at p (corners with a side of zero length add nothing). \pre layers fit mesh, u #V.
double fan_angle(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base, const Eigen::VectorXcd& u,
                 int p);

/// 4·(1 − Θ_p / 2π) rounded, the map's quarter index at every interior vertex (0 at boundary and unused vertices);
/// corners with a side of zero length add no angle (as metrics/param_quality.h cones_from_uv). \return #V \pre uv is #F.
Eigen::VectorXi map_quarter_index(const Mesh& mesh, const Eigen::MatrixX3cd& uv);

struct RingRewinding {
  std::vector<int> rewound;  ///< vertices whose ring was laid out again (ascending)
  /// Vertices with a wrong winding left as they are: a ring vertex held (a branch point, a curve constraint), or a
  /// fan too small for its angle (some corner would need π or more: the fold refinement splits the ring first).
  std::vector<int> skipped;
  std::vector<int> moved;  ///< the vertices the new layouts moved (ascending): rings and moved centres
  /// Branch points whose disk was laid out again (param/cone_disk_layout.h; ascending): also in `rewound`, their
  /// disks' vertices not in `moved` (the layout keeps the disk's boundary: nothing beyond it needs holding).
  std::vector<int> disks;
  std::vector<int> disk_interiors;  ///< the vertices the disks' layouts moved (p excluded; in disk order)
};

/// Lays out again, for every interior vertex p with map_quarter_index(φ) ≠ target[p], the ring of p in
/// φ = base − layered_values(mesh, layers, u) (see above); p itself stays. Branch points come first, each with the
/// disk of param/cone_disk_layout.h where one exists (listed in out.disks), then the rings in vertex order. Returns
/// the new u (u0 elsewhere).
/// `fixed`: 2·#V flags of the held components (param/untangle.h); a ring with a held component is skipped, and so
/// is a fan whose winding is not defined (a side of zero length, or a corner angle within 1e-6 of ±π).
/// \pre layers fit mesh (the transitions preserve them off the branch points); fixed 2·#V, u0 and target #V.
/// Deterministic (vertices in index order).
Eigen::VectorXcd rewind_rings(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                              const Eigen::VectorXcd& u0, const std::vector<char>& fixed,
                              const Eigen::VectorXi& target, RingRewinding& out);
inline constexpr int kRewindPasses = 3;
/// untangle_map (param/untangle.h), then up to kRewindPasses times, while the map has a non-positive triangle or a
/// wrong winding: rewind_rings on the result and untangle_map again, first with the moved vertices held (left free,
/// the untangling would wind the rings back to where they were), then with them free if folds are left; kept if the
/// pair (non-positive triangles, wrong windings) falls in lexicographic order, the order of pipeline/validity_retries.h
/// (a flip traded for a regular vertex at 4π next to the cone is progress); a pass that laid out cone disks and
/// leaves no non-positive triangle polishes their interiors (polish_map). With options.release_curve_corners and
/// release_near_wrong_windings, a pass that is not kept is tried once more with the `releasable` components within
/// 2 rings of the wrongly wound vertices free, kept for fewer wrong windings at no more non-positive triangles (those
/// vertices join released_vertices; later passes keep them free). The record is the last kept pass's, with
/// non_positive_before, the iterations and the released vertices of all passes, the rewound vertices in
/// rewound_vertices and among them the branch points whose disk was laid out again in cone_disk_vertices.
/// target: per vertex the field's cross-field quarter index (field/indices.h); other arguments as untangle_map's.
/// \throw NumericalError if a factorization fails.
Eigen::VectorXcd untangle_and_rewind(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                                     const FramePairs& Z, const std::vector<char>& fixed, const Eigen::VectorXcd& u0,
                                     const Eigen::VectorXi& target, const UntangleOptions& options,
                                     ProgressSink& progress, ParamDiagnostics::Untangling& result,
                                     const std::vector<char>& releasable = {});

}  // namespace quadcover
