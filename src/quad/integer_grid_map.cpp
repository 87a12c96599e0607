#include "common/quarter_turn.h"
#include "quad/integer_grid_map.h"

#include <algorithm>
#include <cmath>

namespace quadcover::grid {

int local_corner(const Mesh& mesh, int f, int v) { return mesh.corner_of(f, v); }

namespace {

// Raw seam transform from face f across its local edge k (valid for interior mesh edges).
void raw_transition(const Mesh& mesh, const Parameterization& param, I64 scale, int f, int k, int& r, IPt& t) {
  const int e = mesh.FE()(f, k);
  const int kr = mod4(param.transition_rotation.size() ? param.transition_rotation[e] : 0);
  const Complex c = param.transition_translation.size() ? param.transition_translation[e] : Complex(0, 0);
  const IPt cs{static_cast<I64>(std::llround(c.real())) * scale, static_cast<I64>(std::llround(c.imag())) * scale};
  if (mesh.EF()(e, 0) == f) {  // φ_t = i^k φ_s + c
    r = kr;
    t = cs;
  } else {  // φ_s = i^{-k} (φ_t - c)
    r = (4 - kr) & 3;
    t = rot({-cs.x, -cs.y}, r);
  }
}

/// The multiple of ½ nearest to x.
double nearest_half_integer(double x) { return std::round(2 * x) / 2; }

double snap_value(double x, double snap) {
  const double h = nearest_half_integer(x);
  return std::abs(x - h) <= snap ? h : x;
}

/// Fixed-point corner coordinates of the map: a power-of-two scale keeping |coordinates| below 2^50 so that
/// orient() products stay far inside 128 bits; values within `snap` of a half-integer are snapped to it, except at
/// the vertices flagged in `unsnapped` (#V, or empty).
void fixed_point_corners(const Mesh& mesh, const Parameterization& param, double snap, double seam_tolerance,
                         const std::vector<char>& unsnapped, GridMap& g) {
  const int nf = mesh.num_faces();
  double max_abs = 1;
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c)
      max_abs = std::max({max_abs, std::abs(param.uv(f, c).real()), std::abs(param.uv(f, c).imag())});
  for (int e = 0; e < param.transition_translation.size(); ++e)
    max_abs = std::max(max_abs, std::abs(param.transition_translation[e]));
  g.shift = std::clamp(50 - static_cast<int>(std::ceil(std::log2(max_abs + 1))), 8, 40);
  g.scale = I64(1) << g.shift;
  const double S = static_cast<double>(g.scale);
  g.q.resize(3 * nf);
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) {
      const Complex z = param.uv(f, c);
      const double to = unsnapped.empty() || !unsnapped[mesh.F()(f, c)] ? snap : -1;
      g.q[3 * f + c] = {static_cast<I64>(std::llround(snap_value(z.real(), to) * S)),
                        static_cast<I64>(std::llround(snap_value(z.imag(), to) * S))};
    }
  for (int e = 0; e < param.transition_translation.size(); ++e) {
    const Complex c = param.transition_translation[e];
    if (std::abs(c - Complex(std::round(c.real()), std::round(c.imag()))) > seam_tolerance)
      ++g.non_integer_translations;
  }
}

/// Makes each vertex's corners exactly consistent: walks its fan and carries the first corner's value across every
/// seam whose transition holds to within seam_tolerance. \return per edge: 1 for the others (torn).
std::vector<char> carry_corners_across_seams(const Mesh& mesh, const Parameterization& param, double seam_tolerance,
                                             GridMap& g) {
  const int nf = mesh.num_faces();
  const I64 tol = std::max<I64>(1, static_cast<I64>(seam_tolerance * static_cast<double>(g.scale)));
  std::vector<char> torn(mesh.num_edges(), 0);
  std::vector<char> done(3 * nf, 0);
  for (int f0 = 0; f0 < nf; ++f0)
    for (int c0 = 0; c0 < 3; ++c0) {
      if (done[3 * f0 + c0]) continue;
      const int v = mesh.F()(f0, c0);
      // Walk clockwise to the start of the fan (a boundary) or all the way round.
      int f = f0, c = c0;
      for (int guard = 0; guard < 4 * nf; ++guard) {
        const int p = mesh.neighbor(f, (c + 2) % 3);
        if (p < 0 || p == f0) break;
        f = p;
        c = local_corner(mesh, f, v);
      }
      const int fs = f;
      done[3 * f + c] = 1;
      for (int guard = 0; guard < 4 * nf; ++guard) {
        const int k = (c + 1) % 3;  // edge along r2 = p_{c+2} - p_c
        const int n = mesh.neighbor(f, k);
        if (n < 0) break;
        const int cn = local_corner(mesh, n, v);
        int r;
        IPt t;
        raw_transition(mesh, param, g.scale, f, k, r, t);
        const IPt carried = rot(g.q[3 * f + c], r) + t;
        IPt& target = g.q[3 * n + cn];
        if (n == fs) {  // closing the cycle: must hold exactly
          if (!(carried == target)) torn[mesh.FE()(f, k)] = 1;
          break;
        }
        if (std::abs(carried.x - target.x) <= tol && std::abs(carried.y - target.y) <= tol)
          target = carried;
        else
          torn[mesh.FE()(f, k)] = 1;
        f = n;
        c = cn;
        done[3 * f + c] = 1;
      }
    }
  return torn;
}

/// Active faces (positive orientation) and their neighbour links across untorn edges, with the transitions.
void link_active_faces(const Mesh& mesh, const Parameterization& param, const std::vector<char>& torn, GridMap& g) {
  const int nf = mesh.num_faces();
  g.active.assign(nf, 0);
  for (int f = 0; f < nf; ++f) {
    const I128 o = orient(g.corner(f, 0), g.corner(f, 1), g.corner(f, 2));
    g.active[f] = o > 0;
    if (o < 0) ++g.flipped_faces;
    if (o == 0) ++g.degenerate_faces;
  }
  g.nb.assign(3 * nf, -1);
  g.nb_rot.assign(3 * nf, 0);
  g.nb_trans.assign(3 * nf, IPt{});
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int n = mesh.neighbor(f, k);
      if (n < 0 || !g.active[f] || !g.active[n] || torn[mesh.FE()(f, k)]) continue;
      g.nb[3 * f + k] = n;
      raw_transition(mesh, param, g.scale, f, k, g.nb_rot[3 * f + k], g.nb_trans[3 * f + k]);
    }
}

/// The quarter-direction slots of sector s: per corner, the directions in its half-open angle [r1, r2) (closed at
/// the end of an open fan), in counter-clockwise order.
void add_sector_slots(const GridMap& g, Sector& s) {
  for (std::size_t i = 0; i < s.corners.size(); ++i) {
    const int fc = s.corners[i], ff = fc / 3, cc = fc % 3;
    const IPt p = g.q[fc], r1 = g.corner(ff, (cc + 1) % 3) - p, r2 = g.corner(ff, (cc + 2) % 3) - p;
    const bool closed_end = !s.cyclic && i + 1 == s.corners.size();
    std::vector<int> dirs;
    for (int d = 0; d < 4; ++d) {
      const IPt w = dir_vec(d);
      const I128 a = cross(r1, w), b = cross(w, r2);
      if (a >= 0 && (b > 0 || (closed_end && b == 0)) && !(a == 0 && dot(r1, w) < 0) && !(b == 0 && dot(w, r2) < 0))
        dirs.push_back(d);
    }
    std::sort(dirs.begin(), dirs.end(), [&](int d1, int d2) {
      const I128 a1 = cross(r1, dir_vec(d1)), a2 = cross(r1, dir_vec(d2));
      if (a1 == 0) return a2 != 0;  // along r1 comes first
      if (a2 == 0) return false;
      return cross(dir_vec(d1), dir_vec(d2)) > 0;
    });
    for (int d : dirs) s.slots.push_back({ff, d});
  }
}

/// Sectors over active faces and holding seams, with their quarter-direction slots in counter-clockwise order.
void build_sectors(const Mesh& mesh, GridMap& g) {
  const int nf = mesh.num_faces();
  g.corner_sector.assign(3 * nf, -1);
  g.corner_pos.assign(3 * nf, -1);
  for (int f0 = 0; f0 < nf; ++f0) {
    if (!g.active[f0]) continue;
    for (int c0 = 0; c0 < 3; ++c0) {
      if (g.corner_sector[3 * f0 + c0] >= 0) continue;
      const int v = mesh.F()(f0, c0);
      Sector s;
      s.vertex = v;
      int f = f0, c = c0;
      s.cyclic = false;
      for (int guard = 0; guard < 4 * nf; ++guard) {
        const int p = g.nb[3 * f + (c + 2) % 3];
        if (p < 0) break;
        if (p == f0) {
          s.cyclic = true;
          f = f0, c = c0;
          break;
        }
        f = p;
        c = local_corner(mesh, f, v);
      }
      const int id = static_cast<int>(g.sectors.size());
      const int fs = f;
      for (int guard = 0; guard < 4 * nf; ++guard) {
        g.corner_sector[3 * f + c] = id;
        g.corner_pos[3 * f + c] = static_cast<int>(s.corners.size());
        s.corners.push_back(3 * f + c);
        const int n = g.nb[3 * f + (c + 1) % 3];
        if (n < 0 || n == fs) break;
        f = n;
        c = local_corner(mesh, f, v);
      }
      add_sector_slots(g, s);
      g.sectors.push_back(std::move(s));
    }
  }
}

/// Flags in `unsnapped` the vertices of the faces that are positive in the map but not in `g` (the snapping moved
/// their corners onto one line), except vertices at lattice points. \return whether it flagged any.
bool unsnap_flattened_faces(const Mesh& mesh, const Parameterization& param, double snap, const GridMap& g,
                            std::vector<char>& unsnapped) {
  bool flagged = false;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (orient(g.corner(f, 0), g.corner(f, 1), g.corner(f, 2)) > 0 || !positive_in_map(param.uv.row(f))) continue;
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.F()(f, c);
      if (unsnapped[v] || at_lattice_point(param.uv(f, c), snap)) continue;
      unsnapped[v] = 1;
      flagged = true;
    }
  }
  return flagged;
}

}  // namespace

bool at_lattice_point(Complex z, double snap) {
  return std::abs(z.real() - nearest_half_integer(z.real())) <= snap &&
         std::abs(z.imag() - nearest_half_integer(z.imag())) <= snap;
}

bool positive_in_map(const Eigen::RowVector3cd& corners) {
  const Complex a = corners[1] - corners[0], b = corners[2] - corners[0], c = corners[2] - corners[1];
  const double longest2 = std::max({std::norm(a), std::norm(b), std::norm(c)});
  return std::imag(std::conj(a) * b) > 1e-12 * longest2;
}

GridMap build_grid_map(const Mesh& mesh, const Parameterization& param, double snap, double seam_tolerance) {
  // Snapping must not flatten a triangle the map keeps positive (a sliver across an iso-line, two vertices a
  // micro-unit apart): those vertices keep their own coordinates; a few passes settle the fans that share them.
  constexpr int kPasses = 3;
  GridMap g;
  std::vector<char> unsnapped(static_cast<std::size_t>(mesh.num_vertices()), 0);
  std::vector<char> torn;
  for (int pass = 0;; ++pass) {
    g = GridMap{};
    g.mesh = &mesh;
    fixed_point_corners(mesh, param, snap, seam_tolerance, unsnapped, g);
    torn = carry_corners_across_seams(mesh, param, seam_tolerance, g);
    if (pass == kPasses || !unsnap_flattened_faces(mesh, param, snap, g, unsnapped)) break;
  }
  g.torn_edges = static_cast<int>(std::count(torn.begin(), torn.end(), 1));
  link_active_faces(mesh, param, torn, g);
  build_sectors(mesh, g);
  return g;
}

}  // namespace quadcover::grid
