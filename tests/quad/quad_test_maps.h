#pragma once
// Integer-grid maps with known quad meshes, built directly in the tests (the parameterization stage is not
// needed): tori with translational seams, cube surfaces with rotational seams and valence-3 branch points, and a
// planar square with boundary.
#include <array>
#include <cmath>
#include <map>
#include <numbers>

#include "mesh/mesh.h"
#include "param/parameterization.h"
#include "quad/transitions.h"
#include "support/test_meshes.h"

namespace quadcover::testing {

struct MeshAndMap {
  Mesh mesh;
  Parameterization param;
};

/// Torus of make_torus(nM, nm) with the map φ(i, j) at its grid vertex (i, j), for 0 <= i <= nM, 0 <= j <= nm (the
/// seams come from φ(i + nM, j) − φ(i, j) and φ(i, j + nm) − φ(i, j)).
template <class Phi>
MeshAndMap torus_map_of(int nM, int nm, const Phi& phi) {
  MeshAndMap r{make_torus(nM, nm), {}};
  Eigen::MatrixX3cd uv(r.mesh.num_faces(), 3);
  for (int i = 0; i < nM; ++i)
    for (int j = 0; j < nm; ++j) {
      const int q = 2 * (i * nm + j);
      uv.row(q) << phi(i, j), phi(i + 1, j), phi(i + 1, j + 1);
      uv.row(q + 1) << phi(i, j), phi(i + 1, j + 1), phi(i, j + 1);
    }
  r.param = parameterization_from_uv(r.mesh, uv);
  return r;
}

/// Torus of make_torus(nM, nm) with φ(i, j) = (P i/nM + shear j/nm + x0, Q j/nm + y0): P·Q quads, all regular.
inline MeshAndMap torus_map(int nM, int nm, int P, int Q, int shear = 0, double x0 = 0.31, double y0 = 0.17) {
  return torus_map_of(nM, nm, [&](int i, int j) {
    return Complex(P * double(i) / nM + shear * double(j) / nm + x0, Q * double(j) / nm + y0);
  });
}

/// The surface of the unit cube, each side an n×n grid, mapped to [0,m]² rotated by i^(side) and shifted by
/// `offset` (use ½(1+i) to put the 8 valence-3 corners at cell centres): 6m² quads and 6m²+2 vertices.
inline MeshAndMap cube_map(int n, int m, Complex offset = {0, 0}) {
  using V3 = Eigen::Vector3d;
  const std::array<std::array<V3, 3>, 6> sides = {{{V3(0, 0, 1), V3(1, 0, 0), V3(0, 1, 0)},
                                                    {V3(0, 0, 0), V3(0, 1, 0), V3(1, 0, 0)},
                                                    {V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 1)},
                                                    {V3(0, 0, 0), V3(0, 0, 1), V3(0, 1, 0)},
                                                    {V3(0, 1, 0), V3(0, 0, 1), V3(1, 0, 0)},
                                                    {V3(0, 0, 0), V3(1, 0, 0), V3(0, 0, 1)}}};
  std::map<std::array<long, 3>, int> index;
  std::vector<V3> pos;
  std::vector<Eigen::Vector3i> tris;
  std::vector<std::array<Complex, 3>> uvs;
  auto vid = [&](const V3& p) {
    const std::array<long, 3> key = {std::lround(p.x() * 4 * n), std::lround(p.y() * 4 * n), std::lround(p.z() * 4 * n)};
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    pos.push_back(p);
    return index[key] = static_cast<int>(pos.size()) - 1;
  };
  for (int s = 0; s < 6; ++s) {
    const auto& [o, a, b] = sides[s];
    auto P = [&](int x, int y) { return V3(o + a * (double(x) / n) + b * (double(y) / n)); };
    auto phi = [&](int x, int y) { return ipow(s) * Complex(double(m) * x / n, double(m) * y / n) + offset; };
    for (int x = 0; x < n; ++x)
      for (int y = 0; y < n; ++y) {
        tris.push_back({vid(P(x, y)), vid(P(x + 1, y)), vid(P(x + 1, y + 1))});
        uvs.push_back({phi(x, y), phi(x + 1, y), phi(x + 1, y + 1)});
        tris.push_back({vid(P(x, y)), vid(P(x + 1, y + 1)), vid(P(x, y + 1))});
        uvs.push_back({phi(x, y), phi(x + 1, y + 1), phi(x, y + 1)});
      }
  }
  Eigen::MatrixX3d V(pos.size(), 3);
  for (std::size_t i = 0; i < pos.size(); ++i) V.row(i) = pos[i].transpose();
  Eigen::MatrixX3i F(tris.size(), 3);
  Eigen::MatrixX3cd uv(tris.size(), 3);
  for (std::size_t i = 0; i < tris.size(); ++i) {
    F.row(i) = tris[i].transpose();
    for (int c = 0; c < 3; ++c) uv(i, c) = uvs[i][c];
  }
  MeshAndMap r{Mesh::from_triangles(V, F), {}};
  r.param = parameterization_from_uv(r.mesh, uv);
  return r;
}

/// The unit square (make_grid(n)) with φ(p) = scale · e^{iθ} p + offset.
inline MeshAndMap square_map(int n, double scale, double theta, Complex offset) {
  MeshAndMap r{make_grid(n), {}};
  Eigen::MatrixX3cd uv(r.mesh.num_faces(), 3);
  for (int f = 0; f < r.mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const auto p = r.mesh.V().row(r.mesh.F()(f, c));
      uv(f, c) = scale * std::polar(1.0, theta) * Complex(p.x(), p.y()) + offset;
    }
  r.param = parameterization_from_uv(r.mesh, uv);
  return r;
}

}  // namespace quadcover::testing
