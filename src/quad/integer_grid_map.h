#pragma once
// An integer-grid map in exact fixed-point arithmetic, the input representation of quad extraction.
// Per-corner coordinates are snapped and quantized to multiples of 1/S (S = 2^shift), then made exactly consistent
// across every seam (φ_t = i^k φ_s + c, thesis 4.2.2) so that all geometric predicates (which side of an iso-line,
// is a grid point inside a triangle) give the same answer in every chart. Faces with non-positive parameter area
// (folds, thesis 2.1 requirement 2) and seams whose transition does not hold are treated as boundary.
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"
#include "param/parameterization.h"

namespace quadcover::grid {

using I64 = std::int64_t;
using I128 = __int128;

struct IPt {
  I64 x = 0, y = 0;
  friend bool operator==(const IPt&, const IPt&) = default;
};
inline IPt operator+(IPt a, IPt b) { return {a.x + b.x, a.y + b.y}; }
inline IPt operator-(IPt a, IPt b) { return {a.x - b.x, a.y - b.y}; }
inline I128 cross(IPt a, IPt b) { return I128(a.x) * b.y - I128(a.y) * b.x; }  ///< \pre none
inline I128 dot(IPt a, IPt b) { return I128(a.x) * b.x + I128(a.y) * b.y; }  ///< \pre none
/// Multiplication by i^k. \pre none
inline IPt rot(IPt p, int k) {
  switch (k & 3) {
    case 0: return p;
    case 1: return {-p.y, p.x};
    case 2: return {-p.x, -p.y};
    default: return {p.y, -p.x};
  }
}
/// Unit direction i^d scaled by len. \pre none
inline IPt dir_vec(int d, I64 len = 1) { return rot({len, 0}, d); }
/// orient(a, b, c) > 0 iff a, b, c are counter-clockwise. \pre none
inline I128 orient(IPt a, IPt b, IPt c) { return cross(b - a, c - a); }

/// A quarter direction i^dir in the chart of `face`, leaving a grid vertex.
struct Slot {
  int face;
  int dir;
  friend bool operator==(const Slot&, const Slot&) = default;
};

/// The corners around one vertex joined through seams that hold (a fan, possibly cut by boundary / folds).
struct Sector {
  int vertex = -1;
  bool cyclic = false;
  std::vector<int> corners;  ///< 3·face + corner, counter-clockwise
  std::vector<Slot> slots;   ///< all quarter directions around the vertex, counter-clockwise
};

struct GridMap {
  const Mesh* mesh = nullptr;
  int shift = 0;
  I64 scale = 1;           ///< S: one grid unit in fixed point
  std::vector<IPt> q;      ///< 3·#F corner coordinates (fixed point)
  std::vector<char> active;  ///< #F: parameter area > 0
  std::vector<int> nb;       ///< 3·#F: face across local edge k if the seam holds and both faces are active, else -1
  std::vector<int> nb_rot;   ///< 3·#F: Q_nb = i^rot Q_f + trans
  std::vector<IPt> nb_trans;
  std::vector<Sector> sectors;
  std::vector<int> corner_sector, corner_pos;  ///< 3·#F: sector of an active corner and its index there; -1 else

  // what was repaired
  int flipped_faces = 0, degenerate_faces = 0, torn_edges = 0, non_integer_translations = 0;

  const IPt& corner(int f, int c) const { return q[3 * f + c]; }  ///< \pre 0 <= f < #F, 0 <= c < 3
  /// \pre 0 <= f < #F, 0 <= k < 3
  IPt to_neighbor(int f, int k, IPt p) const { return rot(p, nb_rot[3 * f + k]) + nb_trans[3 * f + k]; }
  bool is_grid_value(I64 v) const { return v % scale == 0; }  ///< \pre scale > 0
  double to_double(I64 v) const { return static_cast<double>(v) / static_cast<double>(scale); }  ///< \pre scale > 0
};

/// Whether a triangle with these corner coordinates is positive in the map, robustly: its height is more than
/// 1e-12 of its longest edge. \pre none
bool positive_in_map(const Eigen::RowVector3cd& corners);

/// Whether both coordinates of z are within `snap` of multiples of ½ (a lattice point: where cones sit). \pre none
bool at_lattice_point(Complex z, double snap);

/// Builds the exact map. `snap` (grid units): coordinates this close to a multiple of ½ are snapped onto it
/// (branch points of odd index sit at such points, thesis 4.2.2), except at the vertices of a triangle that is
/// positive_in_map but would not be positive after it (unless at a lattice point); `seam_tolerance`: how far the two
/// sides of a seam may disagree before the seam counts as torn. \pre param.uv is #F by 3; its transitions are empty or
/// #E. The map keeps a pointer to mesh. \throw only std::bad_alloc.
GridMap build_grid_map(const Mesh& mesh, const Parameterization& param, double snap, double seam_tolerance);

/// Index of local corner of face f at vertex v, or -1. \pre 0 <= f < #F
int local_corner(const Mesh& mesh, int f, int v);

}  // namespace quadcover::grid
