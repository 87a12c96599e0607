#include "quad/smooth_quads.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <string>

#include "common/errors.h"
#include "field/feature_alignment.h"
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
  // Per undirected edge: number of faces, and whether a quad has it. h = mean length of the quads' edges.
  std::map<std::pair<int, int>, std::pair<int, bool>> edges;
  for (const auto& f : q.faces)
    for (std::size_t k = 0; k < f.size(); ++k) {
      auto& [count, in_quad] = edges[std::minmax(f[k], f[(k + 1) % f.size()])];
      ++count;
      in_quad = in_quad || f.size() == 4;
    }
  double length_sum = 0;
  int quad_edges = 0;
  for (const auto& [e, info] : edges) {
    if (info.first == 1) fixed[e.first] = fixed[e.second] = 1;
    if (info.second) length_sum += (q.V.row(e.first) - q.V.row(e.second)).norm(), ++quad_edges;
  }
  for (const auto& f : q.faces)
    if (f.size() != 4)
      for (int v : f) fixed[v] = 1;
  const double h = quad_edges ? length_sum / quad_edges : 0;
  if (!(h > 0)) return report;
  report.edge_length = h;
  // Vertices on sharp feature edges of the input (put there by curve alignment) stay on them.
  std::vector<char> sharp(mesh.num_edges(), 0);
  for (int e : feature_constraints(mesh).feature_edges) sharp[e] = 1;
  for (int v = 0; v < nv; ++v) {
    const int t = q.source_face[v];
    if (t < 0 || t >= mesh.num_faces()) {
      fixed[v] = 1;
      continue;
    }
    for (int k = 0; k < 3 && !fixed[v]; ++k) {
      if (!sharp[mesh.FE()(t, k)]) continue;
      const Eigen::Vector3d a = mesh.V().row(mesh.F()(t, (k + 1) % 3)), b = mesh.V().row(mesh.F()(t, (k + 2) % 3)),
                            p = q.V.row(v);
      const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      if ((a + s * (b - a) - p).norm() <= options.feature_tolerance * h) fixed[v] = 1;
    }
  }

  // (quad, corner) pairs of each vertex.
  std::vector<std::vector<std::pair<int, int>>> corners(nv);
  for (int f = 0; f < nf; ++f)
    if (q.faces[f].size() == 4)
      for (int k = 0; k < 4; ++k) corners[q.faces[f][k]].push_back({f, k});
  for (int v = 0; v < nv; ++v) {
    if (corners[v].empty()) fixed[v] = 1;
    report.fixed_vertices += fixed[v];
  }

  const TriangleTree tree(mesh.V(), mesh.F());
  const Eigen::MatrixX3d original = q.V;
  const auto surface_normal = [&](int v) -> Eigen::Vector3d { return mesh.face_normals().row(q.source_face[v]); };
  // Number of corners of quad f that turn against the surface normal.
  const auto bad_corners = [&](int f) {
    int bad = 0;
    for (int k = 0; k < 4; ++k) bad += !corner_positive(q.V, q.faces[f], k, surface_normal(q.faces[f][k]));
    return bad;
  };

  std::vector<SquareFit> fits(nf);
  std::vector<int> bad_before(nf, 0);
  for (int it = 0; it < options.iterations && !progress.cancelled(); ++it) {
    // Local step: the target square of every quad.
    tbb::parallel_for(0, nf, [&](int f) {
      if (q.faces[f].size() != 4) return;
      Eigen::Vector3d p[4];
      for (int k = 0; k < 4; ++k) p[k] = q.V.row(q.faces[f][k]);
      fits[f] = fit_square(p, h, options.rigidity);
      bad_before[f] = bad_corners(f);
    });
    // Global step (Jacobi): each free vertex moves tangentially towards the mean of its targets, then onto the
    // surface.
    const Eigen::MatrixX3d before = q.V;
    const Eigen::VectorXi face_before = q.source_face;
    tbb::parallel_for(0, nv, [&](int v) {
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
      const Eigen::Vector3d p = before.row(v), n = surface_normal(v);
      Eigen::Vector3d d = target / count - p;
      d -= d.dot(n) * n;
      const Eigen::Vector3d moved = p + options.step * d;
      int face = -1;
      const Eigen::Vector3d projected = tree.closest_point(moved, &face);
      if (face < 0) return;
      q.V.row(v) = projected;
      q.source_face[v] = face;
    });
    // Undo the moves of quads that got a new inside-out corner, until none does.
    for (bool changed = true; changed;) {
      changed = false;
      for (int f = 0; f < nf; ++f) {
        if (q.faces[f].size() != 4 || bad_corners(f) <= bad_before[f]) continue;
        for (int v : q.faces[f])
          if (q.source_face[v] != face_before[v] || q.V.row(v) != before.row(v)) {
            q.V.row(v) = before.row(v);
            q.source_face[v] = face_before[v];
            ++report.rejected_moves;
            changed = true;
          }
      }
    }
    ++report.iterations;
    progress.report("smooth quads", static_cast<double>(it + 1) / options.iterations,
                    "round " + std::to_string(it + 1));
  }

  // φ at the new points (barycentric interpolation in the source triangle).
  double moved_sum = 0;
  int moved_count = 0;
  for (int v = 0; v < nv; ++v) {
    if (fixed[v]) continue;
    const double dist = (q.V.row(v) - original.row(v)).norm() / h;
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
  return report;
}

}  // namespace quadcover
