#include "quad/smooth_quads.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <numbers>
#include <string>

#include "common/errors.h"
#include "common/union_find.h"
#include "field/feature_alignment.h"
#include "mesh/segment_grid.h"
#include "mesh/triangle_tree.h"

namespace quadcover {
namespace {

using Complex = std::complex<double>;

// Corners of the unit reference square, counter-clockwise, centred at 0 (side 2: scaled by h/2 below).
constexpr Complex kSquare[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};

// The square fitted to one quad: corner k of the target is centre + Re(z·Q_k)·e1 + Im(z·Q_k)·e2.
struct SquareFit {
  Eigen::Vector3d centre, e1, e2;
  Complex z;
  bool valid = false;
};

SquareFit fit_square(const Eigen::Vector3d (&p)[4], double h, double rigidity) {
  SquareFit s;
  s.centre = (p[0] + p[1] + p[2] + p[3]) / 4;
  Eigen::Vector3d n = (p[2] - p[0]).cross(p[3] - p[1]);
  if (n.norm() <= 0) return s;
  n.normalize();
  Eigen::Vector3d e1 = (p[1] - p[0]) + (p[2] - p[3]);
  e1 -= e1.dot(n) * n;
  if (e1.norm() <= 0) return s;
  s.e1 = e1.normalized();
  s.e2 = n.cross(s.e1);
  // Best similarity x ≈ z·(h/2)·Q: z = Σ conj(Q_k) x_k / Σ |Q_k|² (Σ |Q_k|² = 8).
  Complex a = 0;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d d = p[k] - s.centre;
    a += std::conj(kSquare[k]) * Complex(d.dot(s.e1), d.dot(s.e2));
  }
  a /= 8 * (h / 2);
  if (std::abs(a) <= 0) return s;
  // Rotation of the similarity, size blended between h (|z| = 1) and the quad's own.
  const double size = rigidity + (1 - rigidity) * std::abs(a);
  s.z = a / std::abs(a) * size * (h / 2);
  s.valid = true;
  return s;
}

// Whether corner k of polygon f turns counter-clockwise around the surface normal n.
bool corner_positive(const Eigen::MatrixX3d& V, const std::vector<int>& f, int k, const Eigen::Vector3d& n) {
  const int m = static_cast<int>(f.size());
  const Eigen::Vector3d p = V.row(f[k]), next = V.row(f[(k + 1) % m]), prev = V.row(f[(k + m - 1) % m]);
  return (next - p).cross(prev - p).dot(n) > 0;
}

// Input vertices where a feature curve ends or turns by more than 40° (the continuation rule of
// field/feature_alignment.cpp).
std::vector<char> feature_corners(const Mesh& mesh, const std::vector<int>& feature_edges) {
  std::vector<std::vector<int>> at(static_cast<std::size_t>(mesh.num_vertices()));
  for (int e : feature_edges)
    for (int j = 0; j < 2; ++j) at[static_cast<std::size_t>(mesh.E()(e, j))].push_back(e);
  std::vector<char> corner(static_cast<std::size_t>(mesh.num_vertices()), 0);
  const double continues = -std::cos(40.0 * std::numbers::pi / 180.0);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const auto& edges = at[static_cast<std::size_t>(v)];
    const auto away = [&](int e) {
      const int w = mesh.E()(e, 0) == v ? mesh.E()(e, 1) : mesh.E()(e, 0);
      return Eigen::Vector3d((mesh.V().row(w) - mesh.V().row(v)).normalized());
    };
    if (!edges.empty()) corner[v] = edges.size() != 2 || away(edges[0]).dot(away(edges[1])) >= continues;
  }
  return corner;
}

// Chooses the vertices that slide along the features (feature_segment ≥ 0), nearest first: within feature_snap·h
// of a feature (h per vertex: the edge length of its component), unless a quad would get two opposite corners or three
// corners on features, or an edge of a quad would get shorter than h/2 (measured to the neighbour's projection if it
// slides). Vertices already on a feature that may not slide, and those at a feature corner, become fixed.
void snap_to_features(const QuadMesh& q, const Mesh& mesh, const std::vector<int>& feature_edges,
                      const SegmentGrid& grid, const std::vector<std::vector<std::pair<int, int>>>& corners,
                      const std::vector<double>& h, const QuadSmoothingOptions& options, std::vector<char>& fixed,
                      std::vector<int>& feature_segment) {
  const int nv = q.num_vertices();
  if (grid.num_segments() == 0) return;
  const std::vector<char> corner = feature_corners(mesh, feature_edges);
  std::vector<double> dist(nv, std::numeric_limits<double>::infinity());
  std::vector<Eigen::Vector3d> proj(nv);
  std::vector<int> seg(nv, -1);
  tbb::parallel_for(0, nv, [&](int v) {
    if (fixed[v]) return;
    proj[v] = grid.closest_point(q.V.row(v).transpose(), &seg[v]);
    dist[v] = (proj[v] - q.V.row(v).transpose()).norm();
  });
  const auto on = [&](int v) { return options.feature_tolerance * h[v]; };
  std::vector<int> order;
  for (int v = 0; v < nv; ++v)
    if (!fixed[v] && dist[v] <= std::max(on(v), options.feature_snap * h[v])) order.push_back(v);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return std::pair(dist[a], a) < std::pair(dist[b], b); });
  for (int v : order) {
    const int e = feature_edges[static_cast<std::size_t>(seg[v])];
    bool at_corner = false;
    for (int j = 0; j < 2; ++j) {
      const int w = mesh.E()(e, j);
      at_corner |= corner[w] && (proj[v] - mesh.V().row(w).transpose()).norm() <= on(v);
    }
    bool ok = !at_corner && options.feature_snap > 0;
    for (const auto& [f, k] : corners[v]) {
      const std::vector<int>& face = q.faces[f];
      int sliding = 0;
      for (int j = 1; j < 4 && ok; ++j) {
        const int w = face[(k + j) % 4];
        const bool w_slides = feature_segment[w] >= 0;
        const Eigen::Vector3d pw = w_slides ? proj[w] : Eigen::Vector3d(q.V.row(w).transpose());
        if (j != 2) ok = (pw - proj[v]).norm() >= 0.5 * h[v];  // no edge of the quad collapses
        if (!w_slides) continue;
        ++sliding;
        ok = ok && j != 2;
      }
      ok = ok && sliding <= 1;
    }
    if (ok)
      feature_segment[v] = seg[v];
    else if (dist[v] <= on(v))
      fixed[v] = 1;
  }
}

// The input's boundary as polylines to slide on: its edges binned, and its corners (turns over 40°).
struct BoundaryPolylines {
  std::vector<int> edges;
  SegmentGrid grid;
  std::vector<char> corner;  // per input vertex
  BoundaryPolylines(const Mesh& mesh, std::vector<int> boundary_edges)
      : edges(std::move(boundary_edges)),
        grid(mesh.V(), mesh.edge_endpoints(edges)),
        corner(feature_corners(mesh, edges)) {}
  // Whether a vertex may go from boundary edge s to t in one move: the same edge, or the next one through a vertex
  // that is not a corner.
  bool may_pass(const Mesh& mesh, int s, int t) const {
    if (s == t) return true;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        if (mesh.E()(edges[s], i) == mesh.E()(edges[t], j)) return !corner[mesh.E()(edges[s], i)];
    return false;
  }
};

// The boundary vertices of q that slide (boundary_segment ≥ 0): on the input's boundary, in quads only and in two
// or more of them, not at a corner of the input's boundary. They are taken out of `fixed`.
void slide_on_boundary(const QuadMesh& q, const Mesh& mesh, const BoundaryPolylines& boundary,
                       const std::vector<std::vector<std::pair<int, int>>>& corners, const std::vector<double>& h,
                       std::vector<char>& fixed, std::vector<int>& boundary_segment) {
  if (boundary.grid.num_segments() == 0) return;
  std::vector<int> faces_at(static_cast<std::size_t>(q.num_vertices()), 0);
  for (const auto& f : q.faces)
    for (int v : f) ++faces_at[v];
  const std::vector<char> on_boundary = quad_boundary_vertices(q);
  for (int v = 0; v < q.num_vertices(); ++v) {
    if (!on_boundary[v] || faces_at[v] < 2 || static_cast<int>(corners[v].size()) != faces_at[v]) continue;
    const double on = 1e-6 * h[v];
    int s = -1;
    const Eigen::Vector3d p = q.V.row(v).transpose(), c = boundary.grid.closest_point(p, &s);
    if (s < 0 || (c - p).norm() > on) continue;
    const int e = boundary.edges[static_cast<std::size_t>(s)];
    bool at_corner = false;
    for (int j = 0; j < 2; ++j)
      at_corner |= boundary.corner[mesh.E()(e, j)] && (c - mesh.V().row(mesh.E()(e, j)).transpose()).norm() <= on;
    if (at_corner) continue;
    boundary_segment[v] = s;
    fixed[v] = 0;
  }
}

// The mean length of the quads' edges: over all of q, and per vertex over its connected component (components of
// different densities, param/density.h; 0 where a component has no quad).
struct QuadEdgeLength {
  double h = 0;
  std::vector<double> of_vertex;
};

// Fixed vertices on the boundary (edges of one face) and at corners of non-quads into `fixed`. \return the quads'
// mean edge length.
QuadEdgeLength fix_boundary_and_edge_length(const QuadMesh& q, std::vector<char>& fixed) {
  // Per undirected edge: number of faces, and whether a quad has it.
  std::map<std::pair<int, int>, std::pair<int, bool>> edges;
  for (const auto& f : q.faces)
    for (std::size_t k = 0; k < f.size(); ++k) {
      auto& [count, in_quad] = edges[std::minmax(f[k], f[(k + 1) % f.size()])];
      ++count;
      in_quad = in_quad || f.size() == 4;
    }
  const int nv = q.num_vertices();
  detail::UnionFind components(nv);
  for (const auto& [e, info] : edges) components.unite(e.first, e.second);
  double length_sum = 0;
  int quad_edges = 0;
  std::vector<double> component_sum(static_cast<std::size_t>(nv), 0.0);  // at each component's representative
  std::vector<int> component_edges(static_cast<std::size_t>(nv), 0);
  for (const auto& [e, info] : edges) {
    if (info.first == 1) fixed[e.first] = fixed[e.second] = 1;
    if (!info.second) continue;
    const double length = (q.V.row(e.first) - q.V.row(e.second)).norm();
    length_sum += length, ++quad_edges;
    const int c = components.find(e.first);
    component_sum[c] += length, ++component_edges[c];
  }
  for (const auto& f : q.faces)
    if (f.size() != 4)
      for (int v : f) fixed[v] = 1;
  QuadEdgeLength out{quad_edges ? length_sum / quad_edges : 0, std::vector<double>(static_cast<std::size_t>(nv), 0.0)};
  for (int v = 0; v < nv; ++v) {
    const int c = components.find(v);
    if (component_edges[c] > 0) out.of_vertex[v] = component_sum[c] / component_edges[c];
  }
  return out;
}

// What one smoothing round reads: the quad mesh, the fixed and sliding vertices, the surface to project onto.
struct SmoothingRound {
  QuadMesh& q;
  const Mesh& mesh;
  const QuadSmoothingOptions& options;
  const std::vector<double>& h;  // per vertex: the mean quad edge length of its component
  const std::vector<char>& fixed;
  const std::vector<std::vector<std::pair<int, int>>>& corners;  // (quad, corner) pairs of each vertex
  const std::vector<int>& feature_edges;
  const SegmentGrid& feature_grid;
  const TriangleTree& tree;
  std::vector<int>& feature_segment;  // sliding vertices: the feature edge (index into feature_edges) under it
  const BoundaryPolylines& boundary;
  std::vector<int>& boundary_segment;  // boundary vertices that slide: the boundary edge under it

  int feature_face(int s) const {
    const int e = feature_edges[static_cast<std::size_t>(s)];
    return mesh.face_of_edge(e);
  }
  // On a feature the normal is the mean of the two sides' (a corner of a quad on either side turns around it).
  Eigen::Vector3d surface_normal(int v) const {
    if (feature_segment[v] < 0) return mesh.face_normals().row(q.source_face[v]);
    const int e = feature_edges[static_cast<std::size_t>(feature_segment[v])];
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int j = 0; j < 2; ++j)
      if (mesh.EF()(e, j) >= 0) n += mesh.face_normals().row(mesh.EF()(e, j)).transpose();
    return n.normalized();
  }
  // Number of corners of quad f that turn against the surface normal.
  int bad_corners(int f) const {
    int bad = 0;
    for (int k = 0; k < 4; ++k) bad += !corner_positive(q.V, q.faces[f], k, surface_normal(q.faces[f][k]));
    return bad;
  }

  // Global step (Jacobi): each free vertex moves tangentially towards the mean of its targets, then onto the
  // surface; a sliding vertex moves along its feature polyline (the first round snaps onto it).
  void move_vertices(const std::vector<SquareFit>& fits, const Eigen::MatrixX3d& before) {
    tbb::parallel_for(0, q.num_vertices(), [&](int v) {
      if (fixed[v]) return;
      Eigen::Vector3d target = Eigen::Vector3d::Zero();
      int count = 0;
      for (const auto& [f, k] : corners[v]) {
        const SquareFit& s = fits[f];
        if (!s.valid) continue;
        const Complex c = s.z * kSquare[k];
        target += s.centre + c.real() * s.e1 + c.imag() * s.e2;
        ++count;
      }
      if (count == 0) return;
      const Eigen::Vector3d p = before.row(v);
      if (boundary_segment[v] >= 0) {
        int s = -1;
        const Eigen::Vector3d c = boundary.grid.closest_point(p + options.step * (target / count - p), &s);
        if (s < 0 || !boundary.may_pass(mesh, boundary_segment[v], s)) return;
        const int e = boundary.edges[static_cast<std::size_t>(s)];
        q.V.row(v) = c.transpose();
        q.source_face[v] = mesh.face_of_edge(e);
        boundary_segment[v] = s;
        return;
      }
      if (feature_segment[v] >= 0) {
        int s = -1;
        q.V.row(v) = feature_grid.closest_point(p + options.step * (target / count - p), &s).transpose();
        q.source_face[v] = feature_face(s);
        feature_segment[v] = s;
        return;
      }
      const Eigen::Vector3d n = surface_normal(v);
      Eigen::Vector3d d = target / count - p;
      d -= d.dot(n) * n;
      const Eigen::Vector3d moved = p + options.step * d;
      int face = -1;
      const Eigen::Vector3d projected = tree.closest_point(moved, &face);
      if (face < 0) return;
      q.V.row(v) = projected;
      q.source_face[v] = face;
    });
  }

  // One round: the target square of every quad (local step), move_vertices(), then the moves of quads that got a
  // new inside-out corner are undone until none does. \return the number of undone vertex moves.
  int run(std::vector<SquareFit>& fits, std::vector<int>& bad_before) {
    const int nf = q.num_faces();
    tbb::parallel_for(0, nf, [&](int f) {
      if (q.faces[f].size() != 4) return;
      Eigen::Vector3d p[4];
      for (int k = 0; k < 4; ++k) p[k] = q.V.row(q.faces[f][k]);
      fits[f] = fit_square(p, h[q.faces[f][0]], options.rigidity);
      bad_before[f] = bad_corners(f);
    });
    const Eigen::MatrixX3d before = q.V;
    const Eigen::VectorXi face_before = q.source_face;
    const std::vector<int> segment_before = feature_segment, boundary_before = boundary_segment;
    move_vertices(fits, before);
    int rejected = 0;
    for (bool changed = true; changed;) {
      changed = false;
      for (int f = 0; f < nf; ++f) {
        if (q.faces[f].size() != 4 || bad_corners(f) <= bad_before[f]) continue;
        for (int v : q.faces[f])
          if (q.source_face[v] != face_before[v] || q.V.row(v) != before.row(v)) {
            q.V.row(v) = before.row(v);
            q.source_face[v] = face_before[v];
            feature_segment[v] = segment_before[v];
            boundary_segment[v] = boundary_before[v];
            ++rejected;
            changed = true;
          }
      }
    }
    return rejected;
  }
};

// φ at the new points of the free vertices (barycentric interpolation in the source triangle), and their
// displacements in units of h.
void interpolate_uv(QuadMesh& q, const Mesh& mesh, const Parameterization& param, const std::vector<char>& fixed,
                    const Eigen::MatrixX3d& original, const std::vector<double>& h, QuadSmoothingReport& report) {
  double moved_sum = 0;
  int moved_count = 0;
  for (int v = 0; v < q.num_vertices(); ++v) {
    if (fixed[v]) continue;
    const double dist = (q.V.row(v) - original.row(v)).norm() / h[v];
    moved_sum += dist;
    ++moved_count;
    report.max_displacement = std::max(report.max_displacement, dist);
    const int t = q.source_face[v];
    const Eigen::Vector3d a = mesh.V().row(mesh.F()(t, 0)), b = mesh.V().row(mesh.F()(t, 1)),
                          c = mesh.V().row(mesh.F()(t, 2)), p = q.V.row(v);
    const Eigen::Vector3d nrm = (b - a).cross(c - a);
    const double area = nrm.squaredNorm();
    if (area <= 0) continue;
    const double wb = (p - a).cross(c - a).dot(nrm) / area, wc = (b - a).cross(p - a).dot(nrm) / area;
    q.uv[v] = (1 - wb - wc) * param.uv(t, 0) + wb * param.uv(t, 1) + wc * param.uv(t, 2);
  }
  report.mean_displacement = moved_count ? moved_sum / moved_count : 0;
}

}  // namespace

QuadSmoothingReport smooth_quads(QuadMesh& q, const Mesh& mesh, const Parameterization& param,
                                 const QuadSmoothingOptions& options, ProgressSink& progress) {
  QuadSmoothingReport report;
  const int nv = q.num_vertices(), nf = q.num_faces();
  if (options.iterations <= 0 || nv == 0) return report;
  if (q.source_face.size() != nv || q.uv.size() != nv)
    throw InputError("smooth_quads", 0, "the quad mesh has no source face or uv per vertex (not from extract_quads)");
  if (param.uv.rows() != mesh.num_faces())
    throw InputError("smooth_quads", 0, "the parameterization does not belong to the mesh (uv rows != faces)");

  // Fixed vertices: on the boundary (edges of one face), corners of non-quads, on sharp feature edges (below).
  std::vector<char> fixed(nv, 0);
  const QuadEdgeLength lengths = fix_boundary_and_edge_length(q, fixed);
  if (!(lengths.h > 0)) return report;
  report.edge_length = lengths.h;
  const std::vector<double>& h = lengths.of_vertex;
  // (quad, corner) pairs of each vertex.
  std::vector<std::vector<std::pair<int, int>>> corners(nv);
  for (int f = 0; f < nf; ++f)
    if (q.faces[f].size() == 4)
      for (int k = 0; k < 4; ++k) corners[q.faces[f][k]].push_back({f, k});
  for (int v = 0; v < nv; ++v) {
    const int t = q.source_face[v];
    if (corners[v].empty() || t < 0 || t >= mesh.num_faces()) fixed[v] = 1;
  }
  // Sharp feature curves of the input: vertices on or near them slide along them, their corners stay.
  const std::vector<int> feature_edges = feature_constraints(mesh, options.features).feature_edges;
  const SegmentGrid feature_grid(mesh.V(), mesh.edge_endpoints(feature_edges));
  std::vector<int> feature_segment(nv, -1);
  snap_to_features(q, mesh, feature_edges, feature_grid, corners, h, options, fixed, feature_segment);
  const BoundaryPolylines boundary(mesh, options.slide_boundary ? mesh.boundary_edges() : std::vector<int>{});
  std::vector<int> boundary_segment(nv, -1);
  slide_on_boundary(q, mesh, boundary, corners, h, fixed, boundary_segment);
  for (int v = 0; v < nv; ++v) {
    report.fixed_vertices += fixed[v];
    report.feature_vertices += feature_segment[v] >= 0;
    report.boundary_vertices += boundary_segment[v] >= 0;
  }

  const TriangleTree tree(mesh.V(), mesh.F());
  const Eigen::MatrixX3d original = q.V;
  SmoothingRound round{q,
                       mesh,
                       options,
                       h,
                       fixed,
                       corners,
                       feature_edges,
                       feature_grid,
                       tree,
                       feature_segment,
                       boundary,
                       boundary_segment};
  std::vector<SquareFit> fits(nf);
  std::vector<int> bad_before(nf, 0);
  for (int it = 0; it < options.iterations && !progress.skip_improvements(); ++it) {
    report.rejected_moves += round.run(fits, bad_before);
    ++report.iterations;
    progress.report("smooth quads", static_cast<double>(it + 1) / options.iterations,
                    "round " + std::to_string(it + 1));
  }
  interpolate_uv(q, mesh, param, fixed, original, h, report);
  return report;
}

}  // namespace quadcover
