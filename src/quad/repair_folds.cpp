#include "quad/repair_folds.h"

#include <algorithm>
#include <set>

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
  return {1.0 / a, -c / a};                   // φ_s = (φ_t − c) / a
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

}  // namespace

FoldRepairResult repair_folds(const Mesh& mesh, const Parameterization& param, const FoldRepairOptions& options) {
  FoldRepairResult r;
  r.uv = param.uv;
  const int nf = mesh.num_faces();
  auto bad_faces = [&](double threshold) {
    std::vector<int> bad;
    for (int f = 0; f < nf; ++f)
      if (signed_area(r.uv, f) <= threshold) bad.push_back(f);
    return bad;
  };
  std::vector<int> bad = bad_faces(options.min_area);
  r.bad_before = static_cast<int>(bad_faces(0.0).size());
  if (bad.empty()) return r;
  std::set<int> moving;
  for (int f : bad)
    for (int c = 0; c < 3; ++c) moving.insert(mesh.F()(f, c));
  std::vector<char> touched(mesh.num_vertices(), 0);
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
        const Complex p = sum / static_cast<double>(fan.corners.size());
        for (std::size_t j = 0; j < fan.corners.size(); ++j) {
          const auto [f, c] = fan.corners[j];
          r.uv(f, c) = fan.from_first[j](p);
        }
        touched[v] = 1;
      }
    // Tutte averaging is only guaranteed to untangle star-shaped rings: never accept a round that makes it worse.
    const int now = static_cast<int>(bad_faces(0.0).size());
    if (now > best) {
      r.uv = before;
      touched = touched_before;
    } else {
      best = now;
    }
    bad = bad_faces(options.min_area);
    // grow by one ring around what is still bad
    for (int f : bad)
      for (int c = 0; c < 3; ++c)
        for (const auto& fc : mesh.fan(mesh.F()(f, c)))
          for (int cc = 0; cc < 3; ++cc) moving.insert(mesh.F()(fc.face, cc));
  }
  r.bad_after = static_cast<int>(bad_faces(0.0).size());
  r.moved_vertices = static_cast<int>(std::count(touched.begin(), touched.end(), 1));
  return r;
}

}  // namespace quadcover
