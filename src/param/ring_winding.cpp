// The winding of the map around a vertex, and the ring layout that corrects it (see ring_winding.h).
#include "param/ring_winding.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include "mesh/vertex_rings.h"
#include "param/cone_disk_layout.h"

namespace quadcover {

namespace {

constexpr double kPi = std::numbers::pi;

/// The signed angle at corner c of face f in the map (0 if a side has zero length).
double corner_angle(const Complex& at, const Complex& next, const Complex& prev) {
  const Complex e1 = next - at, e2 = prev - at;
  return std::abs(e1) > 0 && std::abs(e2) > 0 ? std::arg(e2 / e1) : 0.0;
}

/// The quarter index 4·(1 − Θ / 2π) of an angle sum Θ, rounded.
int quarter_index_of_angle(double theta) { return static_cast<int>(std::lround(4 - 2 * theta / kPi)); }

/// The angle sum Θ = (4 − q)·π/2 of a quarter index q (the inverse of quarter_index_of_angle).
double angle_of_quarter_index(int q) { return (4 - q) * kPi / 2; }

}  // namespace

double fan_angle(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base, const Eigen::VectorXcd& u,
                 int p) {
  double sum = 0;
  for (const auto& fc : mesh.fan(p))
    sum += corner_angle(corner_value(mesh, layers, base, u, fc.face, fc.corner),
                        corner_value(mesh, layers, base, u, fc.face, (fc.corner + 1) % 3),
                        corner_value(mesh, layers, base, u, fc.face, (fc.corner + 2) % 3));
  return sum;
}

namespace {

/// The fan of p in the chart of its first face: per fan face j, the ring vertex q_j (the corner after p), M_j (the
/// chart of face j is i^{M_j} times the first one's, both centred on φ(p)), the current angle at p.
struct Fan {
  std::vector<int> ring, M;
  std::vector<double> angle;
  bool held = false;       ///< a ring vertex is a branch point or has a held component
  bool undefined = false;  ///< a side of zero length or a corner angle at ±π: the winding is not defined
};

Fan develop(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base, const Eigen::VectorXcd& u,
            const std::vector<char>& fixed, int p) {
  const int nv = mesh.num_vertices();
  Fan fan;
  int M = 0;
  const auto corners = mesh.fan(p);
  for (std::size_t j = 0; j < corners.size(); ++j) {
    const int f = corners[j].face, c = corners[j].corner;
    const int q = mesh.F()(f, (c + 1) % 3);
    fan.held = fan.held || layers.branch[q] || fixed[q] || fixed[nv + q];
    fan.ring.push_back(q);
    fan.M.push_back(M);
    const Complex at = corner_value(mesh, layers, base, u, f, c);
    const Complex next = corner_value(mesh, layers, base, u, f, (c + 1) % 3);
    const Complex prev = corner_value(mesh, layers, base, u, f, (c + 2) % 3);
    fan.angle.push_back(corner_angle(at, next, prev));
    fan.undefined = fan.undefined || next == at || prev == at || std::abs(fan.angle.back()) > kPi - 1e-6;
    // Into the next face across the spoke p–r: φ_g = i^m φ_f + t with m = λ_g(r) − λ_f(r) at the regular r.
    const int r = mesh.F()(f, (c + 2) % 3);
    const int g = corners[(j + 1) % corners.size()].face;
    M += layers.layer(g, mesh.corner_of(g, r)) - layers.layer(f, (c + 2) % 3);
  }
  return fan;
}

/// The new angles at p of the fan faces: the 3D corner angles scaled to add up to `theta`, or equal angles where a
/// scaled one comes near π; empty if even equal ones would.
std::vector<double> target_angles(const Mesh& mesh, int p, double theta) {
  const auto corners = mesh.fan(p);
  const double n = static_cast<double>(corners.size());
  double sum = 0;
  for (const auto& fc : corners) sum += mesh.corner_angles()(fc.face, fc.corner);
  std::vector<double> a;
  if (!(theta > 0)) return a;
  bool too_wide = !(sum > 0);
  for (const auto& fc : corners) {
    a.push_back(sum > 0 ? mesh.corner_angles()(fc.face, fc.corner) * theta / sum : 0.0);
    too_wide = too_wide || a.back() > 0.9 * kPi;
  }
  if (too_wide) std::fill(a.begin(), a.end(), theta / n);
  if (theta / n > 0.9 * kPi) a.clear();
  return a;
}

/// Lays the ring of p out with the angles `a` (see ring_winding.h); returns false if the fan has no extent.
bool lay_out_ring(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base, const Fan& fan,
                  const std::vector<double>& a, int p, Eigen::VectorXcd& u) {
  const auto corners = mesh.fan(p);
  double uv_area = 0, area = 0;
  for (const auto& fc : corners) {
    Complex z[3];
    for (int k = 0; k < 3; ++k) z[k] = corner_value(mesh, layers, base, u, fc.face, k);
    uv_area += 0.5 * std::abs(std::imag(std::conj(z[1] - z[0]) * (z[2] - z[0])));
    area += mesh.face_areas()[fc.face];
  }
  if (!(uv_area > 0 && area > 0)) return false;
  const double s = std::sqrt(uv_area / area);  // grid units per model length around p
  const int f0 = corners[0].face, c0 = corners[0].corner;
  const Complex w0 = corner_value(mesh, layers, base, u, f0, (c0 + 1) % 3) - corner_value(mesh, layers, base, u, f0, c0);
  double alpha = std::abs(w0) > 0 ? std::arg(w0) : 0.0;
  for (std::size_t j = 0; j < corners.size(); ++j) {
    const int f = corners[j].face, c = corners[j].corner, q = fan.ring[j];
    const double rho = s * (mesh.V().row(q) - mesh.V().row(p)).norm();
    const Complex target = corner_value(mesh, layers, base, u, f, c) + ipow(fan.M[j]) * std::polar(rho, alpha);
    const int cq = (c + 1) % 3;
    u[q] += ipow(-layers.layer(f, cq)) * (corner_value(mesh, layers, base, u, f, cq) - target);
    alpha += a[j];
  }
  return true;
}

/// Moves a free vertex p (not a branch point, no held component) to a point of its ring's polygon around which the
/// ring winds by `theta`: the polygon's area centroid or the mean of its vertices, whichever does (the first where
/// every fan angle is in (0, π), else the first with the winding). Returns false if neither does.
bool move_centre(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base, const Fan& fan,
                 double theta, int p, Eigen::VectorXcd& u) {
  const auto corners = mesh.fan(p);
  const std::size_t n = corners.size();
  std::vector<Complex> a(n), b(n);  // per fan face, its two ring corners in the chart of the first face, around φ(p)
  for (std::size_t j = 0; j < n; ++j) {
    const int f = corners[j].face, c = corners[j].corner;
    const Complex centre = corner_value(mesh, layers, base, u, f, c), turn = ipow(-fan.M[j]);
    a[j] = turn * (corner_value(mesh, layers, base, u, f, (c + 1) % 3) - centre);
    b[j] = turn * (corner_value(mesh, layers, base, u, f, (c + 2) % 3) - centre);
  }
  Complex mean = 0, centroid = 0;
  double area = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const double cross = std::imag(std::conj(a[j]) * b[j]);
    mean += a[j] / static_cast<double>(n);
    centroid += cross * (a[j] + b[j]) / 3.0;
    area += cross;
  }
  std::vector<Complex> candidates{mean};
  if (std::abs(area) > 0) candidates.insert(candidates.begin(), centroid / area);
  int chosen = -1;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    double sum = 0;
    bool positive = true;
    for (std::size_t j = 0; j < n; ++j) {
      const double angle = corner_angle(candidates[k], a[j], b[j]);
      sum += angle;
      positive = positive && angle > 0 && std::imag(std::conj(a[j] - candidates[k]) * (b[j] - candidates[k])) > 0;
    }
    if (std::abs(sum - theta) > 0.1) continue;
    if (chosen < 0) chosen = static_cast<int>(k);
    if (positive) {
      chosen = static_cast<int>(k);
      break;
    }
  }
  if (chosen < 0) return false;
  u[p] -= ipow(-layers.layer(corners[0].face, corners[0].corner)) * candidates[chosen];
  return true;
}

}  // namespace

Complex corner_value(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                     const Eigen::VectorXcd& u, int f, int c) {
  const int p = mesh.F()(f, c);
  return base(f, c) - layered_value(layers, f, c, p, u[p]);
}

Eigen::VectorXi map_quarter_index(const Mesh& mesh, const Eigen::MatrixX3cd& uv) {
  const int nv = mesh.num_vertices();
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(nv);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) theta[mesh.F()(f, c)] += corner_angle(uv(f, c), uv(f, (c + 1) % 3), uv(f, (c + 2) % 3));
  Eigen::VectorXi q = Eigen::VectorXi::Zero(nv);
  for (int p = 0; p < nv; ++p)
    if (!mesh.is_boundary_vertex(p) && !mesh.fan(p).empty()) q[p] = quarter_index_of_angle(theta[p]);
  return q;
}

Eigen::VectorXcd rewind_rings(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                              const Eigen::VectorXcd& u0, const std::vector<char>& fixed,
                              const Eigen::VectorXi& target, RingRewinding& out) {
  out = {};
  Eigen::VectorXcd u = u0;
  // Branch points first: a disk laid out again around one also rewinds the regular vertex beside it.
  for (int p = 0; p < mesh.num_vertices(); ++p) {
    if (!layers.branch[p] || mesh.is_boundary_vertex(p) || mesh.fan(p).size() < 3) continue;
    const double theta = angle_of_quarter_index(target[p]);
    if (theta <= 0 || quarter_index_of_angle(fan_angle(mesh, layers, base, u, p)) == target[p]) continue;
    const std::vector<int> inside = lay_out_cone_disk(mesh, layers, base, fixed, theta, p, u);
    if (inside.empty()) continue;
    out.disk_interiors.insert(out.disk_interiors.end(), inside.begin(), inside.end());
    out.disks.push_back(p);
    out.rewound.push_back(p);
  }
  for (int p = 0; p < mesh.num_vertices(); ++p) {
    if (mesh.is_boundary_vertex(p) || mesh.fan(p).size() < 3) continue;
    const Fan fan = develop(mesh, layers, base, u, fixed, p);
    double theta = 0;
    for (double a : fan.angle) theta += a;
    if (quarter_index_of_angle(theta) == target[p]) continue;
    const int nv = mesh.num_vertices();
    const bool free = !layers.branch[p] && !fixed[p] && !fixed[nv + p];
    if (free && !fan.undefined && move_centre(mesh, layers, base, fan, angle_of_quarter_index(target[p]), p, u)) {
      out.rewound.push_back(p);
      out.moved.push_back(p);
      continue;
    }
    const std::vector<double> a =
        fan.held || fan.undefined ? std::vector<double>{} : target_angles(mesh, p, angle_of_quarter_index(target[p]));
    if (a.empty() || !lay_out_ring(mesh, layers, base, fan, a, p, u)) {
      out.skipped.push_back(p);
      continue;
    }
    out.rewound.push_back(p);
    out.moved.insert(out.moved.end(), fan.ring.begin(), fan.ring.end());
  }
  std::sort(out.rewound.begin(), out.rewound.end());
  std::sort(out.moved.begin(), out.moved.end());
  out.moved.erase(std::unique(out.moved.begin(), out.moved.end()), out.moved.end());
  return u;
}

namespace {

/// The inputs of untangle_and_rewind that every pass shares.
struct RewindInputs {
  const Mesh& mesh;
  const VertexLayers& layers;
  const Eigen::MatrixX3cd& base;
  const FramePairs& Z;
  const Eigen::VectorXi& target;
  const UntangleOptions& options;
  ProgressSink& progress;
  const std::vector<char>& releasable;

  Eigen::VectorXi wound(const Eigen::VectorXcd& u) const {
    return map_quarter_index(mesh, base - layered_values(mesh, layers, u));
  }
  int wrong(const Eigen::VectorXcd& u) const { return static_cast<int>((wound(u).array() != target.array()).count()); }
};

struct RewindPass {
  Eigen::VectorXcd u;
  ParamDiagnostics::Untangling result;
  RingRewinding rings;
  int wrong = 0;
};

/// One pass with the components `fixed` held: rewind_rings on u, then untangle_map with the moved vertices held,
/// then with them free if folds are left. Empty rings.rewound: nothing was laid out, or a stop was asked (u empty).
RewindPass rewind_pass(const RewindInputs& in, const std::vector<char>& fixed, const Eigen::VectorXcd& u) {
  RewindPass pass;
  const Eigen::VectorXcd start = rewind_rings(in.mesh, in.layers, in.base, u, fixed, in.target, pass.rings);
  if (in.progress.cancelled()) pass.rings.rewound.clear();
  if (pass.rings.rewound.empty()) return pass;
  std::vector<char> held = fixed;
  for (int q : pass.rings.moved) held[q] = held[in.mesh.num_vertices() + q] = 1;
  ParamDiagnostics::Untangling& r = pass.result;
  pass.u = untangle_map(in.mesh, in.layers, in.base, in.Z, held, start, in.options, in.progress, r, in.releasable);
  if (r.non_positive_after > 0) {
    ParamDiagnostics::Untangling r_free;
    pass.u = untangle_map(in.mesh, in.layers, in.base, in.Z, fixed, pass.u, in.options, in.progress, r_free,
                          in.releasable);
    r_free.iterations += r.iterations;
    r_free.regions += r.regions;
    r_free.polish_iterations += r.polish_iterations;
    r_free.seconds += r.seconds;
    r = std::move(r_free);
  }
  // The laid-out disks are stretched where their Tutte layout met the rim: polished inside the injective set.
  if (r.non_positive_after == 0 && !pass.rings.disks.empty())
    pass.u = polish_map(in.mesh, in.layers, in.base, in.Z, fixed, pass.u, pass.rings.disk_interiors, in.options,
                        in.progress, r);
  pass.wrong = in.wrong(pass.u);
  return pass;
}

/// `fixed` without the curve constraints (`releasable`) of the vertices within 2 rings of a vertex around which u
/// winds other than the target: a branch point rounded onto the image of a curve passing a few edges away leaves
/// the strip between them no width, and no winding is right there until the curve may bend around the cone.
/// `freed` receives the vertices given up (ascending).
std::vector<char> loosened_near_wrong(const RewindInputs& in, const std::vector<char>& fixed,
                                      const Eigen::VectorXcd& u, std::vector<int>& freed) {
  const Mesh& mesh = in.mesh;
  const int nv = mesh.num_vertices();
  const Eigen::VectorXi wound = in.wound(u);
  std::vector<char> wrong(static_cast<std::size_t>(nv), 0);
  for (int p = 0; p < nv; ++p) wrong[p] = wound[p] != in.target[p];
  const std::vector<char> near = grow_vertex_rings(mesh, std::move(wrong), 2);
  std::vector<char> loose = fixed;
  freed.clear();
  for (int p = 0; p < nv; ++p) {
    if (!near[p] || in.layers.branch[p]) continue;
    bool any = false;
    for (const int i : {p, nv + p})
      if (in.releasable[i] && loose[i]) loose[i] = 0, any = true;
    if (any) freed.push_back(p);
  }
  return loose;
}

/// `result` followed by the kept `pass`: the pass's record with the counts before, the iterations and the released
/// vertices of both.
void merge_pass(ParamDiagnostics::Untangling& result, RewindPass& pass) {
  ParamDiagnostics::Untangling& r = pass.result;
  r.non_positive_before = result.non_positive_before;
  r.iterations += result.iterations;
  r.regions += result.regions;
  r.polish_iterations += result.polish_iterations;
  r.seconds += result.seconds;
  r.released_vertices.insert(r.released_vertices.end(), result.released_vertices.begin(),
                             result.released_vertices.end());
  std::sort(r.released_vertices.begin(), r.released_vertices.end());
  r.released_vertices.erase(std::unique(r.released_vertices.begin(), r.released_vertices.end()),
                            r.released_vertices.end());
  result = std::move(r);
}

}  // namespace

Eigen::VectorXcd untangle_and_rewind(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                                     const FramePairs& Z, const std::vector<char>& fixed, const Eigen::VectorXcd& u0,
                                     const Eigen::VectorXi& target, const UntangleOptions& options,
                                     ProgressSink& progress, ParamDiagnostics::Untangling& result,
                                     const std::vector<char>& releasable) {
  Eigen::VectorXcd u = untangle_map(mesh, layers, base, Z, fixed, u0, options, progress, result, releasable);
  if (!options.enabled || !options.rewind_rings) return u;
  const RewindInputs in{mesh, layers, base, Z, target, options, progress, releasable};
  int wrong_now = in.wrong(u);
  // Kept if it is more valid in the order of the validity retries (pipeline/validity_retries.h): fewer
  // non-positive triangles, then fewer wrong windings. A fold traded for a regular vertex at 4π beside the cone is
  // progress: every triangle is then positive, and the fold refinement stops there.
  const auto better = [&](const RewindPass& p) {
    return !p.rings.rewound.empty() &&
           std::tie(p.result.non_positive_after, p.wrong) < std::tie(result.non_positive_after, wrong_now);
  };
  std::vector<char> holding = fixed;
  bool loosened = releasable.empty() || !options.release_curve_corners || !options.release_near_wrong_windings;
  std::vector<int> rewound, disks;
  for (int pass = 0; pass < kRewindPasses && (result.non_positive_after > 0 || wrong_now > 0); ++pass) {
    RewindPass p = rewind_pass(in, holding, u);
    if (!better(p) && !loosened && wrong_now > 0 && !progress.cancelled()) {
      loosened = true;  // once: the curve constraints near the wrong windings, given up for the next passes
      std::vector<int> freed;
      std::vector<char> loose = loosened_near_wrong(in, holding, u, freed);
      RewindPass q = freed.empty() ? RewindPass{} : rewind_pass(in, loose, u);
      // Curve constraints are only given up for fewer wrong windings at no more non-positive triangles.
      if (better(q) && q.wrong < wrong_now && q.result.non_positive_after <= result.non_positive_after) {
        holding = std::move(loose);
        q.result.released_vertices.insert(q.result.released_vertices.end(), freed.begin(), freed.end());
        p = std::move(q);
      }
    }
    if (!better(p)) break;
    merge_pass(result, p);
    rewound.insert(rewound.end(), p.rings.rewound.begin(), p.rings.rewound.end());
    disks.insert(disks.end(), p.rings.disks.begin(), p.rings.disks.end());
    u = std::move(p.u);
    wrong_now = p.wrong;
  }
  std::sort(rewound.begin(), rewound.end());
  rewound.erase(std::unique(rewound.begin(), rewound.end()), rewound.end());
  result.rewound_vertices = std::move(rewound);
  std::sort(disks.begin(), disks.end());
  disks.erase(std::unique(disks.begin(), disks.end()), disks.end());
  result.cone_disk_vertices = std::move(disks);
  return u;
}

}  // namespace quadcover
