// The map around a vertex developed into one chart (see map_development.h).
#include "param/map_development.h"

#include <algorithm>
#include <unordered_map>

#include "mesh/vertex_rings.h"
#include "param/ring_winding.h"

namespace quadcover {

namespace {

/// A chart of the walk: φ_f = i^m Z + t for Z in the first face's chart.
struct Chart {
  int face, m;
  Complex t;
};

/// The regular vertex shared by faces f and g (-1 if none).
int shared_regular(const Mesh& mesh, const VertexLayers& layers, int f, int g) {
  for (int c = 0; c < 3; ++c) {
    const int q = mesh.F()(g, c);
    if (!layers.branch[q] && mesh.corner_of(f, q) >= 0) return q;
  }
  return -1;
}

}  // namespace

std::pair<int, Complex> face_transition(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                                        const Eigen::VectorXcd& u, int f, int g, int r) {
  const int cf = mesh.corner_of(f, r), cg = mesh.corner_of(g, r);
  const int m = layers.layer(g, cg) - layers.layer(f, cf);
  return {m, corner_value(mesh, layers, base, u, g, cg) - ipow(m) * corner_value(mesh, layers, base, u, f, cf)};
}

std::vector<std::pair<int, Complex>> developed_around(const Mesh& mesh, const VertexLayers& layers,
                                                      const Eigen::MatrixX3cd& base, const Eigen::VectorXcd& u, int p,
                                                      int rings) {
  const std::vector<int> faces = faces_within_rings(mesh, p, rings - 1);
  std::unordered_map<int, char> reached;
  std::vector<Chart> walk{{mesh.fan(p)[0].face, 0, 0}};
  reached[walk[0].face] = 1;
  for (std::size_t k = 0; k < walk.size(); ++k)
    for (int e = 0; e < 3; ++e) {
      const int f = walk[k].face, g = mesh.neighbor(f, e);
      if (g < 0 || reached.count(g) || !std::binary_search(faces.begin(), faces.end(), g)) continue;
      const int r = shared_regular(mesh, layers, f, g);
      if (r < 0) continue;
      const auto [m, t] = face_transition(mesh, layers, base, u, f, g, r);
      walk.push_back({g, walk[k].m + m, ipow(m) * walk[k].t + t});
      reached[g] = 1;
    }
  std::vector<std::pair<int, Complex>> out;
  for (const Chart& chart : walk)
    for (int c = 0; c < 3; ++c)
      out.emplace_back(mesh.F()(chart.face, c),
                       ipow(-chart.m) * (corner_value(mesh, layers, base, u, chart.face, c) - chart.t));
  return out;
}

}  // namespace quadcover
