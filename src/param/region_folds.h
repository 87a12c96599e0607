#pragma once
// The non-positive triangles of maps that differ only inside an untangling region, counted without measuring the
// whole map again (param/untangle.cpp checks the map after every Newton step of every region).
#include <Eigen/Core>
#include <vector>

#include "cover/complex_stiffness.h"
#include "mesh/mesh.h"

namespace quadcover {

/// The number of faces, of those `stuck` does not flag, that flipped_triangles (param/seams.h) finds non-positive
/// on the map base − layered_values(x + iy) of Y = (x, y), for the Y that differ from the X given at construction
/// only in the components `region_fixed` leaves free. Only the faces with such a corner are measured again. The others
/// keep their areas; their test |A_uv| ≤ τ·A_3D·Σ|A_uv|/ΣA_3D (the sum moves with the region, a little) looks only at
/// those whose |A_uv|/A_3D lies within a factor 2 of the threshold at construction, and at all of them only if the
/// threshold leaves that band. The count agrees with the whole-map one up to rounding (the order of that sum, and
/// |A_uv|/A_3D against the threshold where the whole-map test multiplies).
class RegionFolds {
 public:
  /// \pre layers and base fit mesh; stuck #F flags; region_fixed and X 2·#V entries (x_p at p, y_p at #V + p).
  RegionFolds(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
              const std::vector<char>& stuck, const std::vector<char>& region_fixed, const Eigen::VectorXd& X);
  /// \pre Y has 2·#V entries and equals X in the fixed components.
  int operator()(const Eigen::VectorXd& Y) const;

 private:
  double signed_area(int f, const Eigen::VectorXd& Y) const;  ///< A_uv of face f on Y's map
  double total_uv(const Eigen::VectorXd& Y) const;            ///< Σ|A_uv| over all faces on Y's map

  const Mesh* mesh_;
  const VertexLayers* layers_;
  const Eigen::MatrixX3cd* base_;
  std::vector<int> moving_;      ///< faces with a free corner, ascending
  std::vector<char> counted_;    ///< per face: not stuck
  std::vector<double> still_q_;  ///< q = |A_uv|/A_3D of the counted faces that do not move, with A_uv ≥ 0
  std::vector<double> band_;     ///< the q in (low_, high_]
  double low_ = 0, high_ = 0;    ///< the band: half and twice the threshold τ·ratio at construction
  int below_band_ = 0;           ///< how many q ≤ low_
  int still_always_ = 0;         ///< counted faces that do not move and are non-positive at any ratio
  double still_abs_ = 0;         ///< Σ|A_uv| of the faces that do not move
  double total_3d_ = 0;          ///< Σ A_3D
};

}  // namespace quadcover
