#include "quad/repair_folds.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "quad/integer_grid_map.h"
#include "quad/transitions.h"

namespace quadcover {

namespace {

// z ↦ a z + b with a = i^k: a chart change.
struct Affine {
  Complex a{1, 0}, b{0, 0};
  Complex operator()(Complex z) const { return a * z + b; }
  Complex inverse(Complex z) const { return (z - b) / a; }
  Affine then(const Affine& next) const { return {next.a * a, next.a * b + next.b}; }  // next ∘ this
};

Affine transition(const Mesh& mesh, const Parameterization& p, int f, int k) {
  const int e = mesh.FE()(f, k);
  const Complex a = ipow(p.transition_rotation.size() ? p.transition_rotation[e] : 0);
  const Complex c = p.transition_translation.size() ? p.transition_translation[e] : Complex(0, 0);
  if (mesh.EF()(e, 0) == f) return {a, c};  // φ_t = a φ_s + c
  return {1.0 / a, -c / a};                 // φ_s = (φ_t − c) / a
}

double signed_area(const Eigen::MatrixX3cd& uv, int f) {
  const Complex e1 = uv(f, 1) - uv(f, 0), e2 = uv(f, 2) - uv(f, 0);
  return 0.5 * (e1.real() * e2.imag() - e1.imag() * e2.real());
}

// The fan of an interior vertex with the chart changes from its first face; false for cones and boundary vertices.
struct Fan {
  std::vector<std::pair<int, int>> corners;  // (face, corner), counter-clockwise
  std::vector<Affine> from_first;            // chart of corners[0].face -> chart of corners[j].face
};
bool regular_fan(const Mesh& mesh, const Parameterization& p, int v, Fan& fan) {
  if (mesh.is_boundary_vertex(v) || mesh.fan(v).empty()) return false;
  int f = mesh.fan(v)[0].face, c = grid::local_corner(mesh, f, v);
  const int f0 = f;
  Affine T;
  for (int guard = 0; guard < 1000; ++guard) {
    fan.corners.emplace_back(f, c);
    fan.from_first.push_back(T);
    const int k = (c + 1) % 3;
    const int n = mesh.neighbor(f, k);
    if (n < 0) return false;
    T = T.then(transition(mesh, p, f, k));
    if (n == f0) break;
    f = n;
    c = grid::local_corner(mesh, f, v);
  }
  // Around a regular vertex the charts close up: the composed change is the identity.
  return std::abs(T.a - Complex(1, 0)) < 1e-12 && std::abs(T.b) < 1e-9;
}

// The kernel of a vertex's one-ring in its first chart: where it can sit so that every incident triangle has signed
// area >= margin (det Dφ > 0, thesis 2.1 requirement 2). Intersection of one half-plane per opposite edge q1 → q2
// (x strictly to its left), clipped from a box around the ring (Sutherland–Hodgman). Empty if infeasible.
std::vector<Complex> ring_kernel(const std::vector<std::pair<Complex, Complex>>& edges, double margin) {
  double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  for (const auto& [a, b] : edges)
    for (const Complex z : {a, b}) {
      lo_x = std::min(lo_x, z.real()), hi_x = std::max(hi_x, z.real());
      lo_y = std::min(lo_y, z.imag()), hi_y = std::max(hi_y, z.imag());
    }
  std::vector<Complex> poly = {{lo_x, lo_y}, {hi_x, lo_y}, {hi_x, hi_y}, {lo_x, hi_y}}, next;
  for (const auto& [q1, q2] : edges) {
    const Complex d = q2 - q1;
    // 2 · area(x, q1, q2) = cross(d, x - q1) >= 2 · margin
    auto g = [&](Complex x) { return d.real() * (x - q1).imag() - d.imag() * (x - q1).real() - 2 * margin; };
    next.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Complex a = poly[i], b = poly[(i + 1) % poly.size()];
      const double ga = g(a), gb = g(b);
      if (ga >= 0) next.push_back(a);
      if ((ga >= 0) != (gb >= 0)) next.push_back(a + (b - a) * (ga / (ga - gb)));
    }
    poly.swap(next);
    if (poly.size() < 3) return {};
  }
  return poly;
}

// 2 · signed area of the triangle (x, q1, q2).
double twice_area(Complex q1, Complex q2, Complex x) {
  const Complex d = q2 - q1;
  return d.real() * (x - q1).imag() - d.imag() * (x - q1).real();
}

// argmax_x min_i 2·area(x, q1_i, q2_i): a 2D linear program (max t s.t. g_i(x) ≥ t); its optimum is where three
// of the affine g_i are equal, so all triples are tried (rings are small). t returns the optimal value.
Complex max_min_area_point(const std::vector<std::pair<Complex, Complex>>& edges, double& t) {
  const int n = static_cast<int>(edges.size());
  // g_i(x) = a_i·x + b_i
  std::vector<double> ax(n), ay(n), b(n);
  for (int i = 0; i < n; ++i) {
    const auto [q1, q2] = edges[i];
    const Complex d = q2 - q1;
    ax[i] = -d.imag(), ay[i] = d.real(), b[i] = d.imag() * q1.real() - d.real() * q1.imag();
  }
  Complex best{0, 0};
  t = -INFINITY;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        // g_i = g_j = g_k: (a_i − a_j)·x = b_j − b_i, (a_i − a_k)·x = b_k − b_i
        const double m11 = ax[i] - ax[j], m12 = ay[i] - ay[j], m21 = ax[i] - ax[k], m22 = ay[i] - ay[k];
        const double det = m11 * m22 - m12 * m21;
        if (std::abs(det) < 1e-300) continue;
        const double r1 = b[j] - b[i], r2 = b[k] - b[i];
        const Complex x((r1 * m22 - m12 * r2) / det, (m11 * r2 - r1 * m21) / det);
        double mn = INFINITY;
        for (int l = 0; l < n; ++l) mn = std::min(mn, ax[l] * x.real() + ay[l] * x.imag() + b[l]);
        if (mn > t) t = mn, best = x;
      }
  return best;
}

// Area centroid of a convex polygon (its vertex mean if the area vanishes).
Complex centroid(const std::vector<Complex>& poly) {
  Complex c{0, 0}, mean{0, 0};
  double area = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Complex a = poly[i], b = poly[(i + 1) % poly.size()];
    const double w = a.real() * b.imag() - a.imag() * b.real();
    area += w;
    c += (a + b) * w;
    mean += a;
  }
  return std::abs(area) > 1e-300 ? c / (3 * area) : mean / static_cast<double>(poly.size());
}

// The faces of uv whose signed area is at most `threshold`, in increasing order.
std::vector<int> bad_faces(const Eigen::MatrixX3cd& uv, double threshold) {
  std::vector<int> bad;
  for (int f = 0; f < uv.rows(); ++f)
    if (signed_area(uv, f) <= threshold) bad.push_back(f);
  return bad;
}

// Puts the fan's vertex at p (in the chart of its first face) in every corner of the fan.
void place_vertex(const Fan& fan, Complex p, Eigen::MatrixX3cd& uv) {
  for (std::size_t j = 0; j < fan.corners.size(); ++j) {
    const auto [f, c] = fan.corners[j];
    uv(f, c) = fan.from_first[j](p);
  }
}

// Tutte rounds: the vertices of the bad faces, grown by one ring per round, move to their one-ring averages; a
// round that leaves more flipped triangles is undone.
void tutte_rounds(const Mesh& mesh, const Parameterization& param, const FoldRepairOptions& options,
                  std::vector<int> bad, FoldRepairResult& r, std::vector<char>& touched) {
  // The vertex set grows ring by ring around the bad faces; each vertex's fan is walked once (a fan of valence d
  // around a high-valence vertex would otherwise be re-walked for every bad face touching it).
  const int nv = mesh.num_vertices();
  std::vector<char> in_moving(nv, 0), expanded(nv, 0);
  std::vector<int> moving;
  auto add_moving = [&](int v) {
    if (!in_moving[v]) in_moving[v] = 1, moving.push_back(v);
  };
  for (int f : bad)
    for (int c = 0; c < 3; ++c) add_moving(mesh.F()(f, c));
  std::sort(moving.begin(), moving.end());
  int best = r.bad_before;
  for (int round = 0; round < options.rounds && !bad.empty(); ++round) {
    const Eigen::MatrixX3cd before = r.uv;
    const std::vector<char> touched_before = touched;
    std::vector<std::pair<int, Fan>> fans;
    for (int v : moving) {
      Fan fan;
      if (regular_fan(mesh, param, v, fan)) fans.emplace_back(v, std::move(fan));
    }
    for (int sweep = 0; sweep < options.sweeps; ++sweep)
      for (auto& [v, fan] : fans) {
        // Tutte average of the one-ring in the chart of the first fan face.
        Complex sum{0, 0};
        for (std::size_t j = 0; j < fan.corners.size(); ++j) {
          const auto [f, c] = fan.corners[j];
          sum += fan.from_first[j].inverse(r.uv(f, (c + 1) % 3));
        }
        place_vertex(fan, sum / static_cast<double>(fan.corners.size()), r.uv);
        touched[v] = 1;
      }
    // Tutte averaging is only guaranteed to untangle star-shaped rings: never accept a round that makes it worse.
    const int now = static_cast<int>(bad_faces(r.uv, 0.0).size());
    if (now > best) {
      r.uv = before;
      touched = touched_before;
    } else {
      best = now;
    }
    bad = bad_faces(r.uv, options.min_area);
    // grow by one ring around what is still bad
    for (int f : bad)
      for (int c = 0; c < 3; ++c) {
        const int v = mesh.F()(f, c);
        if (expanded[v]) continue;
        expanded[v] = 1;
        for (const auto& fc : mesh.fan(v))
          for (int cc = 0; cc < 3; ++cc) add_moving(mesh.F()(fc.face, cc));
      }
    std::sort(moving.begin(), moving.end());
  }
}

// The vertices of the bad faces grown by `ring` rings (breadth first: each fan walked once), sorted. in_cand is
// #V scratch, all 0 on entry and on return.
std::vector<int> candidate_vertices(const Mesh& mesh, const std::vector<int>& bad, int ring,
                                    std::vector<char>& in_cand) {
  std::vector<int> cand;
  auto add_cand = [&](int v) {
    if (!in_cand[v]) in_cand[v] = 1, cand.push_back(v);
  };
  for (int f : bad)
    for (int c = 0; c < 3; ++c) add_cand(mesh.F()(f, c));
  for (int g = 0, begin = 0; g < ring; ++g) {
    const int end = static_cast<int>(cand.size());
    for (int k = begin; k < end; ++k)
      for (const auto& fc : mesh.fan(cand[k]))
        for (int cc = 0; cc < 3; ++cc) add_cand(mesh.F()(fc.face, cc));
    begin = end;
  }
  for (int v : cand) in_cand[v] = 0;
  std::sort(cand.begin(), cand.end());
  return cand;
}

// The kernel-sweep position of a fan's vertex (first-chart coordinates): its one-ring's Tutte average when every
// incident triangle stays positive there, else (if it has a bad incident triangle) a point of the ring's kernel,
// else the point maximizing the smallest incident area if that helps. False: the vertex stays.
bool kernel_position(const Fan& fan, const Eigen::MatrixX3cd& uv, double min_area, Complex& p) {
  std::vector<std::pair<Complex, Complex>> edges;
  Complex sum{0, 0};
  bool has_bad = false;
  for (std::size_t j = 0; j < fan.corners.size(); ++j) {
    const auto [f, c] = fan.corners[j];
    const Complex q1 = fan.from_first[j].inverse(uv(f, (c + 1) % 3));
    edges.emplace_back(q1, fan.from_first[j].inverse(uv(f, (c + 2) % 3)));
    sum += q1;
    has_bad |= signed_area(uv, f) <= min_area;
  }
  const double margin = 2 * min_area;
  p = sum / static_cast<double>(edges.size());
  bool ok = true;
  for (const auto& [q1, q2] : edges) {
    const Complex d = q2 - q1;
    ok &= d.real() * (p - q1).imag() - d.imag() * (p - q1).real() >= 2 * margin;
  }
  if (ok) return true;
  if (!has_bad) return false;
  const std::vector<Complex> kernel = ring_kernel(edges, margin);
  if (!kernel.empty()) {
    p = centroid(kernel);
    return true;
  }
  // No valid position: the one maximizing the smallest incident area, taken only if that area grows and no more
  // incident triangles are bad than before (local untangling; the ring may follow later).
  const Complex old_p = fan.from_first[0].inverse(uv(fan.corners[0].first, fan.corners[0].second));
  double t_best = 0;
  const Complex q = max_min_area_point(edges, t_best);
  double t_old = INFINITY;
  int bad_old = 0, bad_new = 0;
  for (const auto& [q1, q2] : edges) {
    t_old = std::min(t_old, twice_area(q1, q2, old_p));
    bad_old += twice_area(q1, q2, old_p) <= 2 * min_area;
    bad_new += twice_area(q1, q2, q) <= 2 * min_area;
  }
  if (!(t_best > t_old + 1e-12) || bad_new > bad_old) return false;
  p = q;
  return true;
}

// Kernel sweeps: each regular vertex near what is still bad moves to kernel_position(). No move makes an incident
// triangle bad, so the bad count never grows; the neighbourhood grows by one ring whenever a sweep makes no
// progress.
void kernel_sweeps(const Mesh& mesh, const Parameterization& param, const FoldRepairOptions& options,
                   FoldRepairResult& r, std::vector<char>& touched) {
  const int nv = mesh.num_vertices();
  std::vector<signed char> regular(nv, -1);
  std::vector<Fan> fan_of(nv);
  auto fan_at = [&](int v) -> const Fan* {
    if (regular[v] < 0) regular[v] = regular_fan(mesh, param, v, fan_of[v]) ? 1 : 0;
    return regular[v] ? &fan_of[v] : nullptr;
  };
  std::vector<int> bad = bad_faces(r.uv, options.min_area);
  std::vector<char> in_cand(nv, 0);
  int ring = 0, stalled = 0;
  for (int sweep = 0; sweep < options.kernel_sweeps && !bad.empty(); ++sweep) {
    for (int v : candidate_vertices(mesh, bad, ring, in_cand)) {
      const Fan* fan = fan_at(v);
      Complex p;
      if (!fan || !kernel_position(*fan, r.uv, options.min_area, p)) continue;
      place_vertex(*fan, p, r.uv);
      touched[v] = 1;
    }
    const std::size_t before = bad.size();
    bad = bad_faces(r.uv, options.min_area);
    if (bad.size() < before) {
      stalled = 0;
    } else if (++stalled >= 2) {
      ring = std::min(ring + 1, options.max_ring);
      stalled = 0;
    }
  }
}

}  // namespace

FoldRepairResult repair_folds(const Mesh& mesh, const Parameterization& param, const FoldRepairOptions& options) {
  FoldRepairResult r;
  r.uv = param.uv;
  const std::vector<int> bad = bad_faces(r.uv, options.min_area);
  r.bad_before = static_cast<int>(bad_faces(r.uv, 0.0).size());
  if (bad.empty()) return r;
  std::vector<char> touched(mesh.num_vertices(), 0);
  tutte_rounds(mesh, param, options, bad, r, touched);
  kernel_sweeps(mesh, param, options, r, touched);
  r.bad_after = static_cast<int>(bad_faces(r.uv, 0.0).size());
  r.moved_vertices = static_cast<int>(std::count(touched.begin(), touched.end(), 1));
  return r;
}

}  // namespace quadcover
