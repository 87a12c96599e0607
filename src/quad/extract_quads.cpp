// Quad extraction: grid vertices, iso-line tracing across triangles and seams, faces from the rotation system.
#include "quad/extract_quads.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <unordered_map>

#include "common/errors.h"
#include "mesh/segment_grid.h"
#include "quad/collapse_degenerate.h"
#include "quad/doublets.h"
#include "quad/integer_grid_map.h"
#include "quad/quadrangulate.h"
#include "quad/repair_folds.h"

namespace quadcover {
using namespace grid;
namespace {

/// The input's boundary point closest to the middle of the side a–b, if it is nearer to that middle than half the
/// side and at least a quarter of the side from either end; its φ is interpolated along the boundary edge in the
/// snapped map's chart of the edge's face. The boundary edges are binned on the first call.
BoundaryMidpoint boundary_midpoints(const Mesh& mesh, const GridMap& g) {
  auto grid = std::make_shared<std::optional<std::pair<SegmentGrid, std::vector<int>>>>();
  return [&mesh, &g, grid](const Eigen::Vector3d& a, const Eigen::Vector3d& b) -> std::optional<BoundaryPoint> {
    if (!*grid) {
      std::vector<int> edges = mesh.boundary_edges();
      grid->emplace(SegmentGrid(mesh.V(), mesh.edge_endpoints(edges)), std::move(edges));
    }
    const double side = (b - a).norm();
    int segment = -1;
    const Eigen::Vector3d p = (*grid)->first.closest_point(0.5 * (a + b), &segment);
    if (segment < 0 || (p - 0.5 * (a + b)).norm() > 0.5 * side || (p - a).norm() < 0.25 * side ||
        (p - b).norm() < 0.25 * side)
      return std::nullopt;
    const int e = (*grid)->second[static_cast<std::size_t>(segment)];
    const int f = mesh.face_of_edge(e);
    const int v0 = mesh.E()(e, 0), v1 = mesh.E()(e, 1);
    const Eigen::Vector3d p0 = mesh.V().row(v0), p1 = mesh.V().row(v1);
    const double t = std::clamp((p - p0).dot(p1 - p0) / std::max((p1 - p0).squaredNorm(), 1e-300), 0.0, 1.0);
    const IPt q0 = g.corner(f, mesh.corner_of(f, v0)), q1 = g.corner(f, mesh.corner_of(f, v1));
    const double s = static_cast<double>(g.scale);
    const std::complex<double> uv{((1 - t) * static_cast<double>(q0.x) + t * static_cast<double>(q1.x)) / s,
                                  ((1 - t) * static_cast<double>(q0.y) + t * static_cast<double>(q1.y)) / s};
    return BoundaryPoint{p, f, uv};
  };
}

enum class GVType { Vertex, Edge, Face, Crossing };
enum SlotKind : char { kNormal = 0, kLinkFwd = 1, kLinkBwd = 2 };

/// A vertex of the output: an integer point of φ (at a mesh vertex, on an edge, inside a face), a non-integer
/// vertex where iso-lines must stop (branch point or boundary vertex on an iso-line), or a boundary crossing.
struct GVert {
  GVType type = GVType::Face;
  int sector = -1;  ///< Vertex
  int face = -1;    ///< chart face (owner)
  int k = -1;       ///< local edge of `face` (Edge, Crossing)
  IPt p;            ///< exact point in the chart of `face` (Vertex, Edge, Face)
  double lambda = 0;  ///< position along edge k of `face`, from corner k+1 to k+2 (Edge, Crossing)
  int axis = 0;       ///< Crossing: 0 = line x = const, 1 = line y = const
  I64 floor_along = 0;  ///< Crossing: ⌊along-line coordinate⌋ in grid units
  I64 line = 0;         ///< Crossing: the constant coordinate of its iso-line (fixed point)
  int slot_begin = 0, slot_end = 0;
};

struct Key {
  long long tag;
  I64 x, y;
  bool operator==(const Key&) const = default;
};
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    std::size_t h = std::hash<long long>()(k.tag);
    h ^= std::hash<I64>()(k.x) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    h ^= std::hash<I64>()(k.y) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    return h;
  }
};

I64 floor_div(I128 a, I128 b) {  // b > 0
  I128 q = a / b;
  if ((a % b != 0) && (a < 0)) --q;
  return static_cast<I64>(q);
}

class Extractor {
 public:
  Extractor(const Mesh& mesh, const GridMap& g, const ExtractOptions& opt) : mesh_(mesh), g_(g), opt_(opt) {}

  ExtractionResult run(ProgressSink& progress) {
    progress.report("extract", 0.0, "grid points");
    collect_vertex_points();
    collect_edge_points();
    collect_face_points();
    collect_crossings();
    progress.report("extract", 0.3, "tracing iso-lines");
    dest_.assign(slots_.size(), -2);
    for (std::size_t h = 0; h < slots_.size(); ++h)
      if (kind_[h] == kNormal) dest_[h] = trace(static_cast<int>(h));
    check_twins();
    link_boundaries();
    progress.report("extract", 0.8, "faces");
    return assemble();
  }

 private:
  const Mesh& mesh_;
  const GridMap& g_;
  const ExtractOptions& opt_;
  std::vector<GVert> gv_;
  std::vector<Slot> slots_;
  std::vector<char> kind_, exterior_;
  std::vector<int> owner_, dest_;
  std::vector<int> sector_gv_;
  std::unordered_map<Key, int, KeyHash> point_gv_, crossing_gv_;
  std::unordered_map<int, std::vector<int>> halfedge_gvs_;  // boundary half-edge 3f+k -> GVs on it
  ExtractionReport rep_;

  I64 S() const { return g_.scale; }
  int nf() const { return mesh_.num_faces(); }

  // ---- building the vertices and their slots (counter-clockwise)
  int add_gv(GVert v, const std::vector<Slot>& sl, bool boundary, bool fwd_aligned, bool bwd_aligned) {
    const int id = static_cast<int>(gv_.size());
    v.slot_begin = static_cast<int>(slots_.size());
    auto push = [&](Slot s, char kind, char ext) {
      slots_.push_back(s);
      kind_.push_back(kind);
      exterior_.push_back(ext);
      owner_.push_back(id);
    };
    if (boundary && !fwd_aligned) push({v.face, 0}, kLinkFwd, 0);
    for (std::size_t i = 0; i < sl.size(); ++i)
      push(sl[i], kNormal, boundary && bwd_aligned && i + 1 == sl.size());
    if (boundary && !bwd_aligned) push({v.face, 0}, kLinkBwd, 1);
    v.slot_end = static_cast<int>(slots_.size());
    gv_.push_back(v);
    return id;
  }

  static bool along(IPt r, int d) { return cross(r, dir_vec(d)) == 0 && dot(r, dir_vec(d)) > 0; }

  void collect_vertex_points() {
    sector_gv_.assign(g_.sectors.size(), -1);
    for (std::size_t si = 0; si < g_.sectors.size(); ++si) {
      const Sector& s = g_.sectors[si];
      const IPt p = g_.q[s.corners[0]];
      const bool integer = g_.is_grid_value(p.x) && g_.is_grid_value(p.y);
      const bool on_line = g_.is_grid_value(p.x) || g_.is_grid_value(p.y);
      // Regular interior vertices on an iso-line are passed through; iso-lines stop at everything else.
      if (!integer && !(on_line && (!s.cyclic || s.slots.size() != 4))) continue;
      std::vector<Slot> sl;
      for (const Slot& slot : s.slots) {
        const IPt ps = g_.corner(slot.face, local_corner(mesh_, slot.face, s.vertex));
        if (integer || ((slot.dir % 2 == 0) ? g_.is_grid_value(ps.y) : g_.is_grid_value(ps.x))) sl.push_back(slot);
      }
      if (!integer && sl.empty()) continue;
      const int f0 = s.corners.front() / 3, c0 = s.corners.front() % 3;
      const int fl = s.corners.back() / 3, cl = s.corners.back() % 3;
      const IPt r1 = g_.corner(f0, (c0 + 1) % 3) - g_.corner(f0, c0);
      const IPt r2 = g_.corner(fl, (cl + 2) % 3) - g_.corner(fl, cl);
      const bool fwd = !sl.empty() && sl.front().face == f0 && along(r1, sl.front().dir);
      const bool bwd = !sl.empty() && sl.back().face == fl && along(r2, sl.back().dir);
      // A straight boundary running along an iso-line: the line passes through (no output vertex).
      if (!integer && !s.cyclic && s.slots.size() == 3 && sl.size() == 2 && fwd && bwd) continue;
      GVert v;
      v.type = GVType::Vertex;
      v.sector = static_cast<int>(si);
      v.face = f0;
      v.p = p;
      sector_gv_[si] = add_gv(v, sl, !s.cyclic, fwd, bwd);
      if (integer) ++rep_.grid_vertices;
    }
  }

  // Integer points strictly inside segment a-b.
  template <class F>
  void segment_points(IPt a, IPt b, F&& emit) const {
    const IPt d = b - a;
    const bool xmajor = std::abs(d.x) >= std::abs(d.y);
    const I64 a0 = xmajor ? a.x : a.y, a1 = xmajor ? a.y : a.x, d0 = xmajor ? d.x : d.y, d1 = xmajor ? d.y : d.x;
    if (d0 == 0) return;
    const I64 lo = std::min(a0, a0 + d0), hi = std::max(a0, a0 + d0);
    for (I64 n = floor_div(lo, S()) + 1; n * S() < hi; ++n) {
      const I128 num = I128(a1) * d0 + I128(n * S() - a0) * d1;  // other coordinate · d0
      if (num % d0 != 0) continue;
      const I64 o = static_cast<I64>(num / d0);
      if (o % S() != 0) continue;
      emit(xmajor ? IPt{n * S(), o} : IPt{o, n * S()});
    }
  }

  void collect_edge_points() {
    for (int f = 0; f < nf(); ++f) {
      if (!g_.active[f]) continue;
      for (int k = 0; k < 3; ++k) {
        const int e = mesh_.FE()(f, k), n = g_.nb[3 * f + k];
        if (n >= 0 && mesh_.EF()(e, 0) != f) continue;  // interior edges belong to EF(e,0)
        const IPt a = g_.corner(f, (k + 1) % 3), b = g_.corner(f, (k + 2) % 3), ev = b - a;
        segment_points(a, b, [&](IPt p) {
          std::vector<Slot> sl;
          bool fwd = false, bwd = false;
          if (n >= 0) {
            for (int d = 0; d < 4; ++d)
              sl.push_back(cross(ev, dir_vec(d)) < 0 ? Slot{n, (d + g_.nb_rot[3 * f + k]) & 3} : Slot{f, d});
          } else {
            std::vector<int> dirs;
            for (int d = 0; d < 4; ++d)
              if (cross(ev, dir_vec(d)) >= 0) dirs.push_back(d);
            std::sort(dirs.begin(), dirs.end(), [&](int d1, int d2) {
              if (along(ev, d1)) return !along(ev, d2);
              if (along(ev, d2)) return false;
              return cross(dir_vec(d1), dir_vec(d2)) > 0;
            });
            for (int d : dirs) sl.push_back({f, d});
            fwd = along(ev, dirs.front());
            bwd = along(IPt{-ev.x, -ev.y}, dirs.back());
          }
          GVert v;
          v.type = GVType::Edge;
          v.face = f;
          v.k = k;
          v.p = p;
          v.lambda = static_cast<double>(dot(p - a, ev)) / static_cast<double>(dot(ev, ev));
          const int id = add_gv(v, sl, n < 0, fwd, bwd);
          point_gv_[{3LL * f + k, p.x, p.y}] = id;
          if (n < 0) halfedge_gvs_[3 * f + k].push_back(id);
          ++rep_.grid_vertices;
        });
      }
    }
  }

  void collect_face_points() {
    for (int f = 0; f < nf(); ++f) {
      if (!g_.active[f]) continue;
      const IPt A = g_.corner(f, 0), B = g_.corner(f, 1), C = g_.corner(f, 2);
      const I64 x0 = floor_div(std::min({A.x, B.x, C.x}), S()), x1 = floor_div(std::max({A.x, B.x, C.x}), S());
      const I64 y0 = floor_div(std::min({A.y, B.y, C.y}), S()), y1 = floor_div(std::max({A.y, B.y, C.y}), S());
      for (I64 X = x0; X <= x1; ++X)
        for (I64 Y = y0; Y <= y1; ++Y) {
          const IPt p{X * S(), Y * S()};
          if (orient(B, C, p) <= 0 || orient(C, A, p) <= 0 || orient(A, B, p) <= 0) continue;
          GVert v;
          v.type = GVType::Face;
          v.face = f;
          v.p = p;
          point_gv_[{3LL * nf() + f, p.x, p.y}] = add_gv(v, {{f, 0}, {f, 1}, {f, 2}, {f, 3}}, false, false, false);
          ++rep_.grid_vertices;
        }
    }
  }

  void collect_crossings() {
    for (int f = 0; f < nf(); ++f) {
      if (!g_.active[f]) continue;
      for (int k = 0; k < 3; ++k) {
        if (g_.nb[3 * f + k] >= 0) continue;
        const IPt a = g_.corner(f, (k + 1) % 3), b = g_.corner(f, (k + 2) % 3), ev = b - a;
        for (int axis = 0; axis < 2; ++axis) {  // axis 0: lines x = n, axis 1: lines y = n
          const I64 a0 = axis == 0 ? a.x : a.y, b0 = axis == 0 ? b.x : b.y;
          const I64 a1 = axis == 0 ? a.y : a.x, b1 = axis == 0 ? b.y : b.x;
          const I64 lo = std::min(a0, b0), hi = std::max(a0, b0);
          for (I64 n = floor_div(lo, S()) + 1; n * S() < hi; ++n) {
            I128 num = I128(a1) * (b0 - a0) + I128(n * S() - a0) * (b1 - a1);  // along coordinate · den
            I128 den = b0 - a0;
            if (den < 0) num = -num, den = -den;
            if (num % (den * S()) == 0) continue;  // a grid point: an edge vertex already
            GVert v;
          v.type = GVType::Crossing;
            v.face = f;
            v.k = k;
            v.axis = axis;
            v.floor_along = floor_div(num, den * S());
            v.line = n * S();
            v.lambda = static_cast<double>(n * S() - a0) / static_cast<double>(b0 - a0);
            const int din = axis == 0 ? (cross(ev, dir_vec(1)) > 0 ? 1 : 3) : (cross(ev, dir_vec(0)) > 0 ? 0 : 2);
            const int id = add_gv(v, {{f, din}}, true, false, false);
            crossing_gv_[{3LL * f + k, axis, n}] = id;
            halfedge_gvs_[3 * f + k].push_back(id);
            ++rep_.boundary_vertices;
          }
        }
      }
    }
  }

  // ---- slot lookup
  int find_slot(int v, Slot s) const {
    for (int h = gv_[v].slot_begin; h < gv_[v].slot_end; ++h)
      if (kind_[h] == kNormal && slots_[h] == s) return h;
    return -1;
  }
  // Direction w leaving the vertex at corner c of f, moved to the sector corner that owns it (half-open angles).
  Slot canonical_at_vertex(int f, int c, int w) const {
    const Sector& s = g_.sectors[g_.corner_sector[3 * f + c]];
    const IPt r2 = g_.corner(f, (c + 2) % 3) - g_.corner(f, c);
    const bool last = !s.cyclic && g_.corner_pos[3 * f + c] + 1 == static_cast<int>(s.corners.size());
    if (along(r2, w) && !last) {
      const int k = (c + 1) % 3;
      return {g_.nb[3 * f + k], (w + g_.nb_rot[3 * f + k]) & 3};
    }
    return {f, w};
  }
  int local_edge(int f, int e) const {
    for (int k = 0; k < 3; ++k)
      if (mesh_.FE()(f, k) == e) return k;
    return -1;
  }

  // Arrival at grid point t in (closed) face f travelling in direction d: the twin slot, or -1.
  int arrive(int f, IPt t, int d, const I128 o[3]) const {
    const int w = (d + 2) & 3;
    const int zeros = (o[0] == 0) + (o[1] == 0) + (o[2] == 0);
    if (zeros >= 2) {
      const int c = o[0] != 0 ? 0 : (o[1] != 0 ? 1 : 2);
      const int v = sector_gv_[g_.corner_sector[3 * f + c]];
      return v < 0 ? -1 : find_slot(v, canonical_at_vertex(f, c, w));
    }
    if (zeros == 1) {
      const int k = o[0] == 0 ? 0 : (o[1] == 0 ? 1 : 2);
      const int n = g_.nb[3 * f + k];
      if (n < 0) {
        const auto it = point_gv_.find({3LL * f + k, t.x, t.y});
        return it == point_gv_.end() ? -1 : find_slot(it->second, {f, w});
      }
      const int e = mesh_.FE()(f, k), s = mesh_.EF()(e, 0);
      int ws = w, ks = k;
      IPt ts = t;
      if (s != f) {
        ts = g_.to_neighbor(f, k, t);
        ws = (w + g_.nb_rot[3 * f + k]) & 3;
        ks = local_edge(s, e);
      }
      const auto it = point_gv_.find({3LL * s + ks, ts.x, ts.y});
      if (it == point_gv_.end()) return -1;
      const IPt ev = g_.corner(s, (ks + 2) % 3) - g_.corner(s, (ks + 1) % 3);
      const Slot canon = cross(ev, dir_vec(ws)) < 0
                             ? Slot{g_.nb[3 * s + ks], (ws + g_.nb_rot[3 * s + ks]) & 3}
                             : Slot{s, ws};
      return find_slot(it->second, canon);
    }
    const auto it = point_gv_.find({3LL * nf() + f, t.x, t.y});
    return it == point_gv_.end() ? -1 : find_slot(it->second, {f, w});
  }

  // Follows the iso-line of half-edge h to the next output vertex; returns the twin slot or -1.
  int trace(int h) {
    const GVert& X = gv_[owner_[h]];
    int f = slots_[h].face, d = slots_[h].dir;
    IPt t;
    switch (X.type) {
      case GVType::Vertex: {
        // the next grid point along the line (a non-integer vertex on an iso-line: the next grid value beyond it)
        const IPt p = g_.corner(f, local_corner(mesh_, f, g_.sectors[X.sector].vertex));
        auto next = [&](I64 a, bool up) { return up ? (floor_div(a, S()) + 1) * S() : -(floor_div(-a, S()) + 1) * S(); };
        t = (d % 2 == 0) ? IPt{next(p.x, d == 0), p.y} : IPt{p.x, next(p.y, d == 1)};
        break;
      }
      case GVType::Edge:
        t = (f == X.face ? X.p : g_.to_neighbor(X.face, X.k, X.p)) + dir_vec(d, S());
        break;
      case GVType::Face: t = X.p + dir_vec(d, S()); break;
      case GVType::Crossing: {
        const I64 along = (d == 0 || d == 1) ? (X.floor_along + 1) * S() : X.floor_along * S();
        t = X.axis == 0 ? IPt{X.line, along} : IPt{along, X.line};
        break;
      }
    }
    const int limit = 2 * nf() + 16;
    for (int step = 0; step < limit; ++step) {
      const IPt P[3] = {g_.corner(f, 0), g_.corner(f, 1), g_.corner(f, 2)};
      const I128 o[3] = {orient(P[1], P[2], t), orient(P[2], P[0], t), orient(P[0], P[1], t)};
      if (o[0] >= 0 && o[1] >= 0 && o[2] >= 0) return arrive(f, t, d, o);
      const IPt dv = dir_vec(d);
      I128 s[3], tt[3];
      for (int c = 0; c < 3; ++c) s[c] = cross(dv, P[c] - t), tt[c] = dot(dv, P[c] - t);
      int exit_edge = -1, exit_corner = -1;
      for (int k = 0; k < 3; ++k)
        if (s[(k + 1) % 3] < 0 && s[(k + 2) % 3] > 0) exit_edge = k;
      if (exit_edge < 0)
        for (int c = 0; c < 3; ++c)
          if (s[c] == 0 && s[(c + 2) % 3] < 0 && s[(c + 1) % 3] > 0) exit_corner = c;
      if (exit_edge < 0 && exit_corner < 0) {
        int z[3], nz = 0;
        for (int c = 0; c < 3; ++c)
          if (s[c] == 0) z[nz++] = c;
        if (nz != 2 || tt[z[0]] == tt[z[1]]) return -1;
        exit_corner = tt[z[0]] > tt[z[1]] ? z[0] : z[1];
      }
      if (exit_edge >= 0) {
        const int n = g_.nb[3 * f + exit_edge];
        if (n < 0) {  // the iso-line leaves the surface
          const int axis = (d % 2 == 0) ? 1 : 0;
          const I64 value = (axis == 1 ? t.y : t.x) / S();
          const auto it = crossing_gv_.find({3LL * f + exit_edge, axis, value});
          return it == crossing_gv_.end() ? -1 : find_slot(it->second, {f, (d + 2) & 3});
        }
        t = g_.to_neighbor(f, exit_edge, t);
        d = (d + g_.nb_rot[3 * f + exit_edge]) & 3;
        f = n;
        continue;
      }
      // through a mesh vertex
      const int sid = g_.corner_sector[3 * f + exit_corner];
      if (sector_gv_[sid] >= 0) return find_slot(sector_gv_[sid], canonical_at_vertex(f, exit_corner, (d + 2) & 3));
      const Sector& sec = g_.sectors[sid];
      const int ns = static_cast<int>(sec.slots.size());
      if (sec.cyclic && ns != 4) return -1;
      const Slot back = canonical_at_vertex(f, exit_corner, (d + 2) & 3);
      int j = -1;
      for (int i = 0; i < ns; ++i)
        if (sec.slots[i] == back) j = i;
      if (j < 0) return -1;
      // straight on: half a turn (two quarter slots) further, on either side for an open fan along the boundary
      const int ja = sec.cyclic ? (j + 2) % 4 : (j + 2 < ns ? j + 2 : j - 2);
      if (ja < 0) return -1;
      const Slot ahead = sec.slots[ja];
      const I64 dist = static_cast<I64>(dot(dv, t - P[exit_corner]));
      const IPt pg = g_.corner(ahead.face, local_corner(mesh_, ahead.face, sec.vertex));
      f = ahead.face;
      d = ahead.dir;
      t = pg + dir_vec(d, dist);
    }
    return -1;
  }

  void check_twins() {
    for (std::size_t h = 0; h < slots_.size(); ++h) {
      if (kind_[h] != kNormal) continue;
      const int t = dest_[h];
      if (t < 0) {
        ++rep_.failed_traces;
        continue;
      }
      if (dest_[t] != static_cast<int>(h)) {
        ++rep_.failed_traces;
        dest_[h] = -1;
      }
    }
  }

  void link_boundaries() {
    std::unordered_map<int, char> seen;
    for (int f = 0; f < nf(); ++f) {
      if (!g_.active[f]) continue;
      for (int k = 0; k < 3; ++k) {
        if (g_.nb[3 * f + k] >= 0 || seen.count(3 * f + k)) continue;
        // Walk the loop: half-edge (f,k) runs from corner k+1 to k+2 with the surface on its left.
        std::vector<int> seq;
        int cf = f, ck = k;
        for (int guard = 0; guard < 3 * nf() + 3; ++guard) {
          seen[3 * cf + ck] = 1;
          const int vs = sector_gv_[g_.corner_sector[3 * cf + (ck + 1) % 3]];
          if (vs >= 0) seq.push_back(vs);
          auto it = halfedge_gvs_.find(3 * cf + ck);
          if (it != halfedge_gvs_.end()) {
            std::vector<int> on = it->second;
            std::sort(on.begin(), on.end(), [&](int x, int y) { return gv_[x].lambda < gv_[y].lambda; });
            seq.insert(seq.end(), on.begin(), on.end());
          }
          const int c = (ck + 2) % 3;
          const int first = g_.sectors[g_.corner_sector[3 * cf + c]].corners.front();
          cf = first / 3;
          ck = (first % 3 + 2) % 3;
          if (cf == f && ck == k) break;
        }
        for (std::size_t i = 0; i < seq.size(); ++i) {
          const GVert& A = gv_[seq[i]];
          const GVert& B = gv_[seq[(i + 1) % seq.size()]];
          const int fa = A.slot_begin, lb = B.slot_end - 1;
          if (kind_[fa] != kLinkFwd) continue;  // aligned boundary: the traced iso-line is the edge
          if (kind_[lb] != kLinkBwd) continue;  // inconsistent; the link stays unresolved
          dest_[fa] = lb;
          dest_[lb] = fa;
        }
      }
    }
  }

  Eigen::Vector3d position(const GVert& v, std::complex<double>& uv) const {
    const auto& V = mesh_.V();
    const auto& F = mesh_.F();
    const double s = static_cast<double>(S());
    switch (v.type) {
      case GVType::Vertex:
        uv = {v.p.x / s, v.p.y / s};
        return V.row(g_.sectors[v.sector].vertex).transpose();
      case GVType::Face: {
        const IPt A = g_.corner(v.face, 0), B = g_.corner(v.face, 1), C = g_.corner(v.face, 2);
        const double tot = static_cast<double>(orient(A, B, C));
        const double w0 = static_cast<double>(orient(B, C, v.p)) / tot, w1 = static_cast<double>(orient(C, A, v.p)) / tot;
        uv = {v.p.x / s, v.p.y / s};
        return (w0 * V.row(F(v.face, 0)) + w1 * V.row(F(v.face, 1)) + (1 - w0 - w1) * V.row(F(v.face, 2))).transpose();
      }
      default: {
        const IPt a = g_.corner(v.face, (v.k + 1) % 3), b = g_.corner(v.face, (v.k + 2) % 3);
        const double l = v.lambda;
        uv = {((1 - l) * a.x + l * b.x) / s, ((1 - l) * a.y + l * b.y) / s};
        if (v.type == GVType::Edge) uv = {v.p.x / s, v.p.y / s};
        return ((1 - l) * V.row(F(v.face, (v.k + 1) % 3)) + l * V.row(F(v.face, (v.k + 2) % 3))).transpose();
      }
    }
  }

  // Closed fold debris dropped, small fold holes (if any was cut) closed away from the boundary, polygons to quads.
  void repair_polygons(QuadMesh& qm) {
    auto inside = [&](const std::vector<int>& loop) {  // no vertex on a triangle at the input's boundary
      for (int v : loop)
        for (int c = 0; c < 3; ++c)
          if (mesh_.is_boundary_vertex(mesh_.F()(qm.source_face[v], c))) return false;
      return true;
    };
    if (g_.flipped_faces + g_.degenerate_faces + g_.torn_edges + rep_.dropped_faces + rep_.degenerate_faces +
            rep_.boundary_slivers >
        0) {
      rep_.dropped_faces += drop_closed_debris(qm);
      rep_.filled_holes = fill_small_holes(qm, 10, inside);
    }
    for (int round = 0, k = 1; opt_.quadrangulate_boundary && round < 4 && k > 0; ++round)
      rep_.boundary_collapsed_triangles += k = collapse_boundary_triangles(qm);
    const QuadrangulateReport qr = quadrangulate_polygons(qm, 8, opt_.quadrangulate_boundary);
    rep_.boundary_split_polygons = qr.boundary_split_polygons, rep_.boundary_merged_polygons = qr.boundary_merged_pairs;
    if (opt_.quadrangulate_boundary && qm.num_quads() < qm.num_faces()) {
      const BoundaryMidpoint midpoint = boundary_midpoints(mesh_, g_);
      rep_.boundary_added_vertices = split_odd_boundary_polygons(qm, midpoint);  // one vertex per polygon
      rep_.boundary_split_polygons += rep_.boundary_added_vertices;
      for (int round = 0, k = 1; round < 4 && k > 0; ++round)  // one collapse around a vertex per call
        rep_.boundary_collapsed_triangles += k = collapse_boundary_sides(qm, midpoint);
    }
    int late_splits = 0, late_merges = 0;
    // Doublets last: a polygon the steps above make quads is never merged into one they cannot.
    if (const int late = remove_doublets(qm); late > 0) {
      rep_.removed_doublets = late;
      const QuadrangulateReport again = quadrangulate_polygons(qm, 8, opt_.quadrangulate_boundary);
      late_splits = again.split_polygons + again.boundary_split_polygons;
      late_merges = again.merged_pairs + again.boundary_merged_pairs;
    }
    rep_.split_polygons = qr.split_polygons + rep_.boundary_split_polygons + late_splits;
    rep_.merged_polygons = qr.merged_pairs + rep_.boundary_merged_polygons + late_merges;
  }
  ExtractionResult assemble() {
    std::vector<char> visited(slots_.size(), 0);
    std::vector<std::vector<int>> faces;
    for (std::size_t h0 = 0; h0 < slots_.size(); ++h0) {
      if (visited[h0] || exterior_[h0] || kind_[h0] == kLinkBwd) continue;
      std::vector<int> verts;
      int h = static_cast<int>(h0);
      bool ok = true;
      do {
        if (visited[h] || exterior_[h] || static_cast<int>(verts.size()) > opt_.max_face_size) {
          ok = false;
          break;
        }
        visited[h] = 1;
        verts.push_back(owner_[h]);
        const int t = dest_[h];
        if (t < 0) {
          ok = false;
          break;
        }
        const GVert& B = gv_[owner_[t]];
        const int n = B.slot_end - B.slot_begin;
        h = B.slot_begin + (t - B.slot_begin + n - 1) % n;  // next edge: clockwise from the twin
      } while (h != static_cast<int>(h0));
      if (!ok) {
        ++rep_.dropped_faces;
        continue;
      }
      std::vector<int> clean;  // without self-loop links (a boundary loop with a single vertex)
      for (std::size_t i = 0; i < verts.size(); ++i)
        if (verts[i] != verts[(i + 1) % verts.size()]) clean.push_back(verts[i]);
      rep_.removed_spikes += remove_spikes(clean);  // x, v, x: v of valence 1 (e.g. three cones merged)
      std::vector<int> sorted = clean;
      std::sort(sorted.begin(), sorted.end());
      if (clean.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
        const bool sliver =
            std::all_of(clean.begin(), clean.end(), [&](int v) { return gv_[v].type == GVType::Crossing; });
        ++(sliver ? rep_.boundary_slivers : rep_.degenerate_faces);
        continue;
      }
      faces.push_back(std::move(clean));
    }
    ExtractionResult res;
    QuadMesh& qm = res.mesh;
    const int ng = static_cast<int>(gv_.size());
    qm.V.resize(ng, 3);
    qm.uv.resize(ng);
    qm.source_face.resize(ng);
    qm.on_grid.resize(ng);
    for (int i = 0; i < ng; ++i) {
      std::complex<double> uv;
      qm.V.row(i) = position(gv_[i], uv).transpose();
      qm.uv[i] = uv;
      qm.source_face[i] = gv_[i].face;
      qm.on_grid[i] = gv_[i].type != GVType::Crossing && g_.is_grid_value(gv_[i].p.x) && g_.is_grid_value(gv_[i].p.y);
    }
    qm.faces = std::move(faces);
    rep_.dropped_faces += drop_faces_on_duplicate_edges(qm);
    rep_.split_vertices = split_pinched_vertices(qm);
    if (opt_.quadrangulate) repair_polygons(qm);
    remove_unused_vertices(qm);  // after the clean-up: dropped faces leave no orphans
    rep_.quads = qm.num_quads(), rep_.non_quads = qm.num_faces() - rep_.quads;  // reported after every repair
    rep_.flipped_triangles = g_.flipped_faces, rep_.degenerate_triangles = g_.degenerate_faces;
    rep_.torn_seams = g_.torn_edges, rep_.non_integer_translations = g_.non_integer_translations;
    for (int f = 0; f < nf(); ++f)
      if (g_.active[f]) {
        const double sc = static_cast<double>(S());
        rep_.active_parameter_area +=
            0.5 * static_cast<double>(orient(g_.corner(f, 0), g_.corner(f, 1), g_.corner(f, 2))) / sc / sc;
      }
    res.report = rep_;
    return res;
  }
};

}  // namespace

ExtractionResult extract_quads(const Mesh& mesh, const Parameterization& param, const ExtractOptions& options,
                               ProgressSink& progress) {
  if (param.uv.rows() != mesh.num_faces())
    throw InputError("", 0, "extract_quads: parameterization has " + std::to_string(param.uv.rows()) +
                                " faces, mesh has " + std::to_string(mesh.num_faces()));
  if ((param.transition_rotation.size() && param.transition_rotation.size() != mesh.num_edges()) ||
      (param.transition_translation.size() && param.transition_translation.size() != mesh.num_edges()))
    throw InputError("", 0, "extract_quads: transitions must have one entry per edge");
  // Edges mapped to a point (e.g. two branch points rounded onto one integer point) are collapsed first.
  CollapsedMap collapsed;
  if (options.collapse_zero_edges) collapsed = collapse_zero_edges(mesh, param, 2 * options.snap);
  const bool use_collapsed = collapsed.collapsed_edges > 0;
  const Mesh& m = use_collapsed ? collapsed.mesh : mesh;
  FoldRepairResult repair;
  const Parameterization* map = use_collapsed ? &collapsed.param : &param;
  Parameterization repaired;
  if (options.repair_folds) {
    repair = repair_folds(m, *map);
    if (repair.moved_vertices > 0) {
      repaired = *map;
      repaired.uv = repair.uv;
      map = &repaired;
    }
  }
  const GridMap g = build_grid_map(m, *map, options.snap, options.seam_tolerance);
  Extractor x(m, g, options);
  ExtractionResult r = x.run(progress);
  r.report.unfolded_triangles = repair.bad_before - repair.bad_after;
  r.report.moved_vertices = repair.moved_vertices;
  r.report.collapsed_edges = collapsed.collapsed_edges;
  if (use_collapsed)  // source faces refer to the input mesh
    for (int v = 0; v < r.mesh.num_vertices(); ++v) r.mesh.source_face[v] = collapsed.face_origin[r.mesh.source_face[v]];
  return r;
}

}  // namespace quadcover
