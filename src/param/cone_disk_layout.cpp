// The disk around a wrongly wound branch point laid out again in its cone chart (see cone_disk_layout.h).
#include "param/cone_disk_layout.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "common/union_find.h"
#include "mesh/segment_grid.h"
#include "mesh/vertex_rings.h"
#include "param/map_development.h"
#include "param/ring_winding.h"

namespace quadcover {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kOnPoint = 1e-9;  // grid units: a boundary vertex this close to φ(p) is on it

/// D: its faces, interior vertices (every face in D), the cut (edges of a shortest path from p to ∂D) and the
/// boundary edges, each as (face, corner c) for the edge from corner c to c + 1.
struct Disk {
  std::vector<int> faces;
  std::unordered_map<int, int> slot;                      ///< face → index in faces
  std::vector<int> interior;                              ///< ascending, with p
  std::unordered_set<int> inside;                         ///< the interior vertices
  std::unordered_set<int> cut;                            ///< edges
  int cut_end = -1;                                       ///< the boundary vertex the cut reaches
  std::unordered_map<int, std::pair<int, int>> out_edge;  ///< boundary vertex → (face, corner) of its outgoing edge
  bool in(int f) const { return f >= 0 && slot.count(f) > 0; }
};

/// The cut of D: a breadth-first path over interior vertices from p to the first boundary vertex reached.
bool cut_disk(const Mesh& mesh, int p, Disk& d) {
  std::unordered_map<int, std::pair<int, int>> prev{{p, {-1, -1}}};  // vertex → (previous vertex, edge)
  std::vector<int> queue{p};
  for (std::size_t k = 0; k < queue.size() && d.cut_end < 0; ++k)
    for (const auto& fc : mesh.fan(queue[k])) {
      const int q = mesh.F()(fc.face, (fc.corner + 1) % 3);
      if (prev.count(q)) continue;
      prev[q] = {queue[k], mesh.FE()(fc.face, (fc.corner + 2) % 3)};
      if (!d.inside.count(q)) {
        d.cut_end = q;
        break;
      }
      queue.push_back(q);
    }
  if (d.cut_end < 0) return false;
  for (int v = d.cut_end; prev[v].first >= 0; v = prev[v].first) d.cut.insert(prev[v].second);
  return true;
}

/// Whether make_disk gave D. Blocked (another branch point or a held vertex inside) holds for every larger k too:
/// D only grows, and a vertex with all its faces in D stays inside.
enum class DiskMade { Made, NotADisk, Blocked };

/// D for `rings`, if it is a disk of interior mesh vertices with only p a branch point or held inside.
DiskMade make_disk(const Mesh& mesh, const VertexLayers& layers, const std::vector<char>& fixed, int p, int rings,
                   Disk& d) {
  const int nv = mesh.num_vertices();
  d.faces = faces_within_rings(mesh, p, rings - 1);  // faces with a vertex within rings − 1 rings
  for (std::size_t k = 0; k < d.faces.size(); ++k) d.slot[d.faces[k]] = static_cast<int>(k);
  std::unordered_map<int, int> vertex_faces, edges;
  for (int f : d.faces)
    for (int c = 0; c < 3; ++c) ++vertex_faces[mesh.F()(f, c)], ++edges[mesh.FE()(f, c)];
  for (const auto& [v, n] : vertex_faces) {
    if (n != static_cast<int>(mesh.fan(v).size()) || mesh.is_boundary_vertex(v)) continue;
    if (v != p && (layers.branch[v] || fixed[v] || fixed[nv + v])) return DiskMade::Blocked;
    d.interior.push_back(v);
    d.inside.insert(v);
  }
  std::sort(d.interior.begin(), d.interior.end());
  const long chi =
      static_cast<long>(vertex_faces.size()) - static_cast<long>(edges.size()) + static_cast<long>(d.faces.size());
  if (chi != 1 || !d.inside.count(p)) return DiskMade::NotADisk;
  for (int f : d.faces)  // boundary edges: one face in D; one outgoing edge per boundary vertex
    for (int c = 0; c < 3; ++c)
      if (edges[mesh.FE()(f, (c + 2) % 3)] == 1 && !d.out_edge.emplace(mesh.F()(f, c), std::pair{f, c}).second)
        return DiskMade::NotADisk;
  if (d.out_edge.empty()) return DiskMade::NotADisk;
  const int v0 = std::min_element(d.out_edge.begin(), d.out_edge.end())->first;
  std::size_t steps = 0;  // the boundary is one loop
  int v = v0;
  do {
    const auto it = d.out_edge.find(v);
    if (it == d.out_edge.end()) return DiskMade::NotADisk;
    v = mesh.F()(it->second.first, (it->second.second + 1) % 3);
    ++steps;
  } while (v != v0 && steps <= d.out_edge.size());
  if (v != v0 || steps != d.out_edge.size()) return DiskMade::NotADisk;
  return cut_disk(mesh, p, d) ? DiskMade::Made : DiskMade::NotADisk;
}

/// φ_f = i^m z + t for z in the chart of p's first fan face, per face of D, by a walk that does not cross the cut.
struct Charts {
  std::vector<int> m;
  std::vector<Complex> t;
  std::vector<char> reached;
};

Charts develop_disk(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                    const Eigen::VectorXcd& u, const Disk& d, int p) {
  const std::size_t n = d.faces.size();
  Charts ch{std::vector<int>(n, 0), std::vector<Complex>(n, 0.0), std::vector<char>(n, 0)};
  const int f0 = mesh.fan(p)[0].face;
  std::vector<int> walk{f0};
  ch.reached[d.slot.at(f0)] = 1;
  for (std::size_t k = 0; k < walk.size(); ++k)
    for (int e = 0; e < 3; ++e) {
      const int f = walk[k], g = mesh.neighbor(f, e);
      if (!d.in(g) || ch.reached[d.slot.at(g)] || d.cut.count(mesh.FE()(f, e))) continue;
      int r = -1;  // a regular vertex of the shared edge
      for (int c : {(e + 1) % 3, (e + 2) % 3})
        if (!layers.branch[mesh.F()(f, c)]) r = mesh.F()(f, c);
      if (r < 0) continue;
      const auto [m, t] = face_transition(mesh, layers, base, u, f, g, r);
      const int sf = d.slot.at(f), sg = d.slot.at(g);
      ch.m[sg] = ch.m[sf] + m;
      ch.t[sg] = ipow(m) * ch.t[sf] + t;
      ch.reached[sg] = 1;
      walk.push_back(g);
    }
  return ch;
}

/// The laid-out disk's corners: per corner (slot·3 + c) of D its copy (corners of one vertex joined across the
/// edges of D off the cut), per copy the vertex, the flattened position w and its continuous argument.
struct Copies {
  std::vector<int> of_corner, vertex;
  std::vector<Complex> w;
  std::vector<double> arg;
  std::vector<char> known;
};

Copies disk_copies(const Mesh& mesh, const Disk& d) {
  const int n = static_cast<int>(3 * d.faces.size());
  detail::UnionFind sets(n);
  for (std::size_t k = 0; k < d.faces.size(); ++k)
    for (int e = 0; e < 3; ++e) {
      const int f = d.faces[k], g = mesh.neighbor(f, e);
      if (!d.in(g) || d.cut.count(mesh.FE()(f, e))) continue;
      for (int c : {(e + 1) % 3, (e + 2) % 3})
        sets.unite(static_cast<int>(3 * k) + c, 3 * d.slot.at(g) + mesh.corner_of(g, mesh.F()(f, c)));
    }
  Copies cp;
  std::unordered_map<int, int> id;
  for (int k = 0; k < n; ++k) {
    const auto [it, added] = id.emplace(sets.find(k), static_cast<int>(cp.vertex.size()));
    if (added) cp.vertex.push_back(mesh.F()(d.faces[k / 3], k % 3));
    cp.of_corner.push_back(it->second);
  }
  cp.w.assign(cp.vertex.size(), 0.0);
  cp.arg.assign(cp.vertex.size(), 0.0);
  cp.known.assign(cp.vertex.size(), 0);
  return cp;
}

/// ∂D in the flattened chart walked from the cut's end: its vertices, positions and continuous arguments, the cut's
/// end again at the end (on the cut's other side, argument + 2π).
struct Rim {
  std::vector<int> vertex;
  std::vector<Complex> w;
  std::vector<double> arg;
};

/// Walks ∂D from the cut's end: the boundary copies get w = r^a e^{i a θ} (θ the argument around L, continuous along
/// the walk; a = 2π / theta). \return the rim, empty unless ∂D sweeps theta around L and avoids it.
Rim flatten_boundary(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                     const Eigen::VectorXcd& u, const Disk& d, const Charts& ch, Complex L, double theta, Copies& cp) {
  const auto developed = [&](int f, int c) {
    const int s = d.slot.at(f);
    return ipow(-ch.m[s]) * (corner_value(mesh, layers, base, u, f, c) - ch.t[s]);
  };
  const double a = 2 * kPi / theta;
  Rim rim;
  const auto set = [&](int f, int c, double arg) {
    const Complex z = developed(f, c) - L;
    const int k = cp.of_corner[3 * d.slot.at(f) + c];
    cp.arg[k] = a * arg;
    cp.w[k] = std::polar(std::pow(std::abs(z), a), a * arg);
    cp.known[k] = 1;
    rim.vertex.push_back(mesh.F()(f, c));
    rim.w.push_back(cp.w[k]);
    rim.arg.push_back(cp.arg[k]);
  };
  const auto [f0, c0] = d.out_edge.at(d.cut_end);
  const Complex z0 = developed(f0, c0) - L;
  if (!(std::abs(z0) > kOnPoint)) return {};
  double arg = std::arg(z0);
  set(f0, c0, arg);
  int v = d.cut_end;
  do {
    const auto [f, c] = d.out_edge.at(v);
    const Complex from = developed(f, c) - L, to = developed(f, (c + 1) % 3) - L;
    if (!(std::abs(to) > kOnPoint)) return {};
    arg += std::arg(to / from);
    v = mesh.F()(f, (c + 1) % 3);
    if (v == d.cut_end && (std::abs(arg - std::arg(z0) - theta) > 0.1 ||
                           cp.of_corner[3 * d.slot.at(f) + (c + 1) % 3] == cp.of_corner[3 * d.slot.at(f0) + c0]))
      return {};
    set(f, (c + 1) % 3, arg);  // at the end: the cut's end again, on the cut's other side
  } while (v != d.cut_end);
  return rim;
}

/// True if the rim is star-shaped around 0: every argument increases along it, every edge turning left around 0.
bool star_shaped(const Rim& rim) {
  for (std::size_t j = 0; j + 1 < rim.arg.size(); ++j)
    if (!(rim.arg[j + 1] > rim.arg[j]) || std::imag(std::conj(rim.w[j]) * rim.w[j + 1]) <= 0) return false;
  return true;
}

/// The homeomorphism from the unit disk onto the flattened disk that sends e^{2πij/n} to ∂D's j-th vertex (n
/// boundary vertices, evenly spaced: p, D's combinatorial centre, then lands near 0): r e^{iψ} ↦ r ρ(θ) e^{iθ}, θ
/// linear in ψ between the vertices' arguments, ρ(θ) the distance from 0 to ∂D along the ray of angle θ.
Complex from_unit_disk(const Rim& rim, Complex v) {
  if (!(std::abs(v) > 0)) return v;
  const double n = static_cast<double>(rim.arg.size() - 1);
  const double psi = std::fmod(std::arg(v) + 2 * kPi, 2 * kPi) * n / (2 * kPi);
  const std::size_t j = std::min(static_cast<std::size_t>(psi), rim.arg.size() - 2);
  const double theta = rim.arg[j] + (psi - static_cast<double>(j)) * (rim.arg[j + 1] - rim.arg[j]);
  const Complex a = rim.w[j], e = rim.w[j + 1] - a, u = std::polar(1.0, theta);
  return std::abs(v) * std::imag(std::conj(a) * e) / std::imag(std::conj(u) * e) * u;
}

/// Tutte's layout of D's interior: every interior vertex at the mean of its neighbours, the boundary vertices at w
/// (a map from vertex to position, completed; empty if the system, the graph Laplacian of D's interior, cannot be
/// factored).
std::unordered_map<int, Complex> barycentric_layout(const Mesh& mesh, const Disk& d,
                                                    std::unordered_map<int, Complex> w) {
  std::unordered_map<int, int> index;  // interior vertex → unknown
  for (int v : d.interior) index.emplace(v, static_cast<int>(index.size()));
  const int n = static_cast<int>(index.size());
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX2d b = Eigen::MatrixX2d::Zero(n, 2);
  for (int v : d.interior) {
    const int i = index.at(v);
    for (const auto& fc : mesh.fan(v)) {  // each neighbour once: the corner after v in its fan faces
      const int q = mesh.F()(fc.face, (fc.corner + 1) % 3);
      entries.emplace_back(i, i, 1.0);
      if (const auto j = index.find(q); j != index.end()) {
        entries.emplace_back(i, j->second, -1.0);
      } else {
        const Complex wq = w.at(q);
        b(i, 0) += wq.real(), b(i, 1) += wq.imag();
      }
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  if (ldlt.info() != Eigen::Success) return {};
  const Eigen::MatrixX2d x = ldlt.solve(b);
  for (int v : d.interior) {
    const int i = index.at(v);
    w[v] = Complex(x(i, 0), x(i, 1));
  }
  return w;
}

/// Distance from c to the segment [a, b] in the plane.
double segment_distance(Complex c, Complex a, Complex b) {
  const auto in_space = [](Complex z) { return Eigen::Vector3d(z.real(), z.imag(), 0); };
  return (in_space(c) - closest_point_on_segment(in_space(c), in_space(a), in_space(b))).norm();
}

/// Moves the layout so that p is at 0 and the boundary stays: w ↦ w − w_p β(|w − w_p| / R), β(t) = (1 − t²)² on
/// [0, 1], R 0.95 of w_p's distance to ∂D; a homeomorphism while |w_p| · max|β'| < R (max|β'| < 1.54). False if not.
bool centre_on_cone(const Mesh& mesh, const Disk& d, int p, std::unordered_map<int, Complex>& w) {
  const Complex c = w.at(p);
  double reach = std::numeric_limits<double>::infinity();
  for (const auto& [v, fc] : d.out_edge)
    reach = std::min(reach, segment_distance(c, w.at(v), w.at(mesh.F()(fc.first, (fc.second + 1) % 3))));
  const double R = 0.95 * reach;
  if (!(1.6 * std::abs(c) < R)) return false;
  for (int v : d.interior) {
    const double t = std::abs(w[v] - c) / R;
    if (t < 1) w[v] -= c * (1 - t * t) * (1 - t * t);
  }
  w[p] = 0.0;
  return true;
}

/// The layout of D's interior around p at 0 (barycentric, then centred), with every copy's continuous argument by a
/// walk from the boundary (arguments of neighbours differ by less than π). False if the rim is not star-shaped, the
/// layout cannot be centred or a vertex but p lands on 0.
bool lay_out_flattened(const Mesh& mesh, const Disk& d, int p, const Rim& rim, Copies& cp) {
  if (!star_shaped(rim)) return false;
  std::unordered_map<int, Complex> w;
  const double n = static_cast<double>(rim.arg.size() - 1);
  for (std::size_t j = 0; j + 1 < rim.arg.size(); ++j)
    w.emplace(rim.vertex[j], std::polar(1.0, 2 * kPi * static_cast<double>(j) / n));
  w = barycentric_layout(mesh, d, std::move(w));
  if (w.empty() || !centre_on_cone(mesh, d, p, w)) return false;
  for (int v : d.interior) w[v] = from_unit_disk(rim, w[v]);
  for (std::size_t k = 0; k < cp.vertex.size(); ++k)
    if (!cp.known[k]) cp.w[k] = w.at(cp.vertex[k]);
  std::vector<std::vector<int>> faces_of(cp.vertex.size());
  for (std::size_t s = 0; s < d.faces.size(); ++s)
    for (int c = 0; c < 3; ++c) faces_of[cp.of_corner[3 * s + c]].push_back(static_cast<int>(s));
  std::vector<int> queue;
  for (std::size_t k = 0; k < cp.vertex.size(); ++k)
    if (cp.known[k]) queue.push_back(static_cast<int>(k));
  for (std::size_t h = 0; h < queue.size(); ++h) {
    const int k = queue[h];
    for (int s : faces_of[k])
      for (int j = 0; j < 3; ++j) {
        const int other = cp.of_corner[3 * s + j];
        if (cp.known[other] || cp.vertex[other] == p) continue;
        if (!(std::abs(cp.w[other]) > kOnPoint)) return false;
        cp.arg[other] = cp.arg[k] + std::arg(cp.w[other] / cp.w[k]);
        cp.known[other] = 1;
        queue.push_back(other);
      }
  }
  return true;
}

/// u with D's interior (but p) moved to the layout: z = L + |w|^{1/a} e^{i arg / a} in the developed chart.
Eigen::VectorXcd mapped_back(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                             const Eigen::VectorXcd& u, const Disk& d, const Charts& ch, const Copies& cp, Complex L,
                             double theta, int p) {
  const double a = 2 * kPi / theta;
  Eigen::VectorXcd out = u;
  for (int q : d.interior) {
    if (q == p) continue;
    const auto fc = mesh.fan(q)[0];
    const int s = d.slot.at(fc.face), k = cp.of_corner[3 * s + fc.corner];
    const Complex z = L + std::polar(std::pow(std::abs(cp.w[k]), 1 / a), cp.arg[k] / a);
    const Complex value = ipow(ch.m[s]) * z + ch.t[s];
    out[q] = ipow(-layers.layer(fc.face, fc.corner)) * (base(fc.face, fc.corner) - value);
  }
  return out;
}

}  // namespace

std::vector<int> lay_out_cone_disk(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                                   const std::vector<char>& fixed, double theta, int p, Eigen::VectorXcd& u) {
  const auto f0 = mesh.fan(p)[0];
  const Complex L = corner_value(mesh, layers, base, u, f0.face, f0.corner);
  for (int rings = 2; rings <= kMaxConeDiskRings; ++rings) {
    Disk d;
    const DiskMade made = make_disk(mesh, layers, fixed, p, rings, d);
    if (made == DiskMade::Blocked || d.faces.size() > kMaxConeDiskFaces) break;
    if (made == DiskMade::NotADisk) continue;
    const Charts ch = develop_disk(mesh, layers, base, u, d, p);
    if (std::count(ch.reached.begin(), ch.reached.end(), 0) > 0) continue;
    Copies cp = disk_copies(mesh, d);
    const Rim rim = flatten_boundary(mesh, layers, base, u, d, ch, L, theta, cp);
    if (rim.arg.empty() || !lay_out_flattened(mesh, d, p, rim, cp)) continue;
    Eigen::VectorXcd laid = mapped_back(mesh, layers, base, u, d, ch, cp, L, theta, p);
    if (std::abs(fan_angle(mesh, layers, base, laid, p) - theta) > 0.1) continue;
    u = std::move(laid);
    std::vector<int> moved;
    for (int q : d.interior)
      if (q != p) moved.push_back(q);
    return moved;
  }
  return {};
}

}  // namespace quadcover
