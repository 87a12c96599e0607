// Functions on the cut disk: integration (1.12), transitions across the cut, Σ̃ potentials (1.13) on the covering.
#include "param/disk_functions.h"

#include <algorithm>
#include <numeric>

#include "common/quarter_turn.h"
#include "cover/complex_stiffness.h"

namespace quadcover {

Complex carry_across(const Mesh& mesh, const CoverCut& cut, const Eigen::VectorXcd& c, const FanCrossing& cr,
                     Complex x) {
  if (!cut.graph.cut[cr.edge]) return x;
  const int k = cut.rotation[cr.edge];
  if (mesh.EF()(cr.edge, 0) == cr.from) return ipow(k) * x + c[cr.edge];  // s -> t
  return ipow(-k) * (x - c[cr.edge]);                                     // t -> s
}

int crossing_rotation(const Mesh& mesh, const CoverCut& cut, const FanCrossing& cr) {
  if (!cut.graph.cut[cr.edge]) return 0;
  return mesh.EF()(cr.edge, 0) == cr.from ? cut.rotation[cr.edge] : -cut.rotation[cr.edge];
}

Eigen::VectorXcd integrate_on_disk(const Mesh& mesh, const CoverCut& cut, const FramePairs& Z) {
  const CutMesh& disk = cut.disk;
  Eigen::VectorXcd u = Eigen::VectorXcd::Zero(disk.num_vertices());
  std::vector<char> known(static_cast<std::size_t>(disk.num_vertices()), 0), seen(mesh.num_faces(), 0);
  std::vector<int> queue;
  for (int root = 0; root < mesh.num_faces(); ++root) {
    if (seen[root]) continue;
    seen[root] = 1;
    known[disk.corner_vertex(root, 0)] = 1;
    queue.assign(1, root);
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int f = queue[q];
      int a = 0;  // a corner of f with a known value (exists: f was reached through an uncut edge or is a root)
      while (!known[disk.corner_vertex(f, a)]) ++a;
      for (int b = 0; b < 3; ++b) {
        const int vb = disk.corner_vertex(f, b);
        if (known[vb]) continue;
        // (1.12): u_q = u_p + ⟨e, Z_t⟩ along the edge from corner a to corner b.
        const Complex e = mesh.corner_local()(f, b) - mesh.corner_local()(f, a);
        u[vb] = u[disk.corner_vertex(f, a)] + frame_dot(e, Z(f, 0), Z(f, 1));
        known[vb] = 1;
      }
      for (int k = 0; k < 3; ++k) {
        const int g = mesh.neighbor(f, k);
        if (g >= 0 && !seen[g] && !cut.graph.cut[mesh.FE()(f, k)]) {
          seen[g] = 1;
          queue.push_back(g);
        }
      }
    }
  }
  return u;
}

Eigen::MatrixX3cd corner_values(const CoverCut& cut, const Eigen::VectorXcd& values) {
  Eigen::MatrixX3cd out(cut.disk.corner_vertex.rows(), 3);
  for (int f = 0; f < out.rows(); ++f)
    for (int c = 0; c < 3; ++c) out(f, c) = values[cut.disk.corner_vertex(f, c)];
  return out;
}

std::pair<Complex, Complex> face_gradient(const Mesh& mesh, const Eigen::MatrixX3cd& phi, int f) {
  const double A2 = 2 * mesh.face_areas()[f];
  Complex gx = 0, gy = 0;
  for (int c = 0; c < 3; ++c) {
    const Complex Je = Complex(0, 1) * mesh.edge_vector_local(f, c) / A2;  // ∇φ_c = J e_c / 2A
    gx += phi(f, c).real() * Je;
    gy += phi(f, c).imag() * Je;
  }
  return {gx, gy};
}

FramePairs corner_gradient(const Mesh& mesh, const Eigen::MatrixX3cd& phi) {
  FramePairs G(mesh.num_faces(), 2);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto [gx, gy] = face_gradient(mesh, phi, f);
    G(f, 0) = gx;
    G(f, 1) = gy;
  }
  return G;
}

Eigen::VectorXcd cut_translations(const Mesh& mesh, const CoverCut& cut, const Eigen::MatrixX3cd& phi,
                                  double* mismatch) {
  Eigen::VectorXcd c = Eigen::VectorXcd::Zero(mesh.num_edges());
  double worst = 0;
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (!cut.graph.cut[e]) continue;
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    const Complex rot = ipow(cut.rotation[e]);
    Complex est[2];
    for (int end = 0; end < 2; ++end) {
      const int v = mesh.E()(e, end);
      est[end] = phi(t, mesh.corner_of(t, v)) - rot * phi(s, mesh.corner_of(s, v));
    }
    c[e] = 0.5 * (est[0] + est[1]);
    worst = std::max(worst, std::abs(est[0] - est[1]));
  }
  if (mismatch) *mismatch = worst;
  return c;
}

void complete_translations(const Mesh& mesh, const CoverCut& cut, Eigen::VectorXcd& c) {
  complete_translations(mesh, cut, cut_fans(mesh, cut), c);
}

void complete_translations(const Mesh& mesh, const CoverCut& cut, const CutFans& fans, Eigen::VectorXcd& c) {
  for (const int k : fans.elimination) {
    const int pe = cut.graph.parent_edge[fans.vertices[k]];
    const auto crossings = fans.crossings_of(k);
    const int d = static_cast<int>(crossings.size());
    int ip = 0;
    while (crossings[ip].edge != pe) ++ip;
    Complex x = 0;  // value at face crossings[ip].to, carried once around
    for (int i = 1; i < d; ++i) x = carry_across(mesh, cut, c, crossings[(ip + i) % d], x);
    // The parent crossing must bring x back to 0.
    const FanCrossing& cr = crossings[ip];
    c[pe] = mesh.EF()(pe, 0) == cr.from ? -ipow(cut.rotation[pe]) * x : x;
  }
}

std::vector<std::vector<std::uint64_t>> path_parities(const Mesh& mesh, const CoverCut& cut) {
  const std::size_t words = (static_cast<std::size_t>(cut.num_paths()) + 63) / 64;
  std::vector<std::vector<std::uint64_t>> bits(mesh.num_edges(), std::vector<std::uint64_t>(words, 0));
  for (int j = 0; j < cut.num_paths(); ++j) bits[cut.path_edge[j]][j / 64] |= std::uint64_t{1} << (j % 64);
  const CutFans fans = cut_fans(mesh, cut);
  for (const int k : fans.elimination) {
    const int pe = cut.graph.parent_edge[fans.vertices[k]];
    std::vector<std::uint64_t> acc(words, 0);
    for (const FanCrossing& cr : fans.crossings_of(k))
      if (cut.graph.cut[cr.edge] && cr.edge != pe)
        for (std::size_t w = 0; w < words; ++w) acc[w] ^= bits[cr.edge][w];
    bits[pe] = acc;
  }
  return bits;
}

namespace {

/// z ↦ i^K z + D composed over `crossings` (a vertex's fan, in order). \pre as carry_across for each crossing.
std::pair<int, Complex> compose_transitions(const Mesh& mesh, const CoverCut& cut, const Eigen::VectorXcd& c,
                                            std::span<const FanCrossing> crossings) {
  int K = 0;
  Complex D = 0;
  for (const FanCrossing& cr : crossings) {
    D = carry_across(mesh, cut, c, cr, D);
    K += crossing_rotation(mesh, cut, cr);
  }
  return {mod4(K), D};
}

/// The fixed point D / (1 − i^K) of a composed transition, 0 where K = 0.
Complex fixed_point(const std::pair<int, Complex>& transition) {
  const auto [K, D] = transition;
  return K == 0 ? Complex(0) : D / (Complex(1) - ipow(K));
}

}  // namespace

std::pair<int, Complex> transition_around(const Mesh& mesh, const CoverCut& cut, const Eigen::VectorXcd& c, int v) {
  return compose_transitions(mesh, cut, c, fan_crossings(mesh, v));
}

Complex branch_point_image(const Mesh& mesh, const CoverCut& cut, const Eigen::VectorXcd& T, int v) {
  return fixed_point(transition_around(mesh, cut, T, v));
}

bool moves_fan(const CoverCut& cut, const CutFans& fans, const Eigen::VectorXcd& c, int k) {
  for (const FanCrossing& cr : fans.crossings_of(k))
    if (cut.graph.cut[cr.edge] && c[cr.edge] != Complex(0)) return true;
  return false;
}

void write_fan_jump(const Mesh& mesh, const CoverCut& cut, const CutFans& fans, const Eigen::VectorXcd& c, int k,
                    Eigen::MatrixX3cd& sigma) {
  const int v = fans.vertices[k];
  const auto fan = mesh.fan(v);
  const auto crossings = fans.crossings_of(k);
  // At a branch point the value is pinned by the rotation around v: x = i^K x + D.
  Complex x = cut.branch[v] ? fixed_point(compose_transitions(mesh, cut, c, crossings)) : Complex(0);
  sigma(fan[0].face, fan[0].corner) = x;
  for (std::size_t i = 0; i + 1 < fan.size(); ++i) {
    x = carry_across(mesh, cut, c, crossings[i], x);
    sigma(fan[i + 1].face, fan[i + 1].corner) = x;
  }
}

Eigen::MatrixX3cd jump_function(const Mesh& mesh, const CoverCut& cut, const Eigen::VectorXcd& c) {
  return jump_function(mesh, cut, cut_fans(mesh, cut), c);
}

Eigen::MatrixX3cd jump_function(const Mesh& mesh, const CoverCut& cut, const CutFans& fans, const Eigen::VectorXcd& c) {
  Eigen::MatrixX3cd sigma = Eigen::MatrixX3cd::Zero(mesh.num_faces(), 3);
  for (int k = 0; k < static_cast<int>(fans.vertices.size()); ++k)
    if (moves_fan(cut, fans, c, k)) write_fan_jump(mesh, cut, fans, c, k, sigma);
  return sigma;
}

}  // namespace quadcover
