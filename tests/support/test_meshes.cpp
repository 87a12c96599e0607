#include "support/test_meshes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include "io/read_mesh.h"

namespace quadcover::testing {

std::string data_path(const std::string& name) {
  std::string p = std::string(QUADCOVER_TEST_DATA_DIR) + "/" + name;
  if (name.find('.') == std::string::npos) p += ".obj";
  return p;
}

Mesh load_test_mesh(const std::string& name) { return build_mesh(read_mesh(data_path(name))).mesh; }

Mesh make_torus(int n_major, int n_minor, double R, double r) {
  Eigen::MatrixX3d V(n_major * n_minor, 3);
  Eigen::MatrixX3i F(2 * n_major * n_minor, 3);
  auto id = [&](int i, int j) { return ((i + n_major) % n_major) * n_minor + (j + n_minor) % n_minor; };
  for (int i = 0; i < n_major; ++i)
    for (int j = 0; j < n_minor; ++j) {
      const double u = 2 * std::numbers::pi * i / n_major, v = 2 * std::numbers::pi * j / n_minor;
      V.row(id(i, j)) << (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v);
      const int q = 2 * (i * n_minor + j);
      F.row(q) << id(i, j), id(i + 1, j), id(i + 1, j + 1);
      F.row(q + 1) << id(i, j), id(i + 1, j + 1), id(i, j + 1);
    }
  return Mesh::from_triangles(V, F);
}

Mesh make_fan(int n, bool closed, double height) {
  Eigen::MatrixX3d V(n + (closed ? 2 : 1), 3);
  Eigen::MatrixX3i F((closed ? 2 : 1) * n, 3);
  V.row(0) << 0, 0, height;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    V.row(i + 1) << std::cos(a), std::sin(a), 0;
    F.row(i) << 0, 1 + i, 1 + (i + 1) % n;
    if (closed) F.row(n + i) << n + 1, 1 + (i + 1) % n, 1 + i;
  }
  if (closed) V.row(n + 1) << 0, 0, -height;
  return Mesh::from_triangles(V, F);
}

Eigen::MatrixX3i grid_faces_with_holes(const Mesh& grid, int n) {
  std::vector<int> keep;
  for (int f = 0; f < grid.num_faces(); ++f) {
    const int quad = f / 2, i = quad % n, j = quad / n;  // make_grid numbers quads row by row, two triangles each
    if (!(i % 2 == 1 && j % 2 == 1 && i < n - 2 && j < n - 2)) keep.push_back(f);
  }
  Eigen::MatrixX3i F(static_cast<Eigen::Index>(keep.size()), 3);
  for (std::size_t k = 0; k < keep.size(); ++k) F.row(static_cast<Eigen::Index>(k)) = grid.F().row(keep[k]);
  return F;
}

Mesh make_grid(int n) {
  Eigen::MatrixX3d V((n + 1) * (n + 1), 3);
  Eigen::MatrixX3i F(2 * n * n, 3);
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) V.row(id(i, j)) << double(i) / n, double(j) / n, 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int q = 2 * (j * n + i);
      F.row(q) << id(i, j), id(i + 1, j), id(i + 1, j + 1);
      F.row(q + 1) << id(i, j), id(i + 1, j + 1), id(i, j + 1);
    }
  return Mesh::from_triangles(V, F);
}

Mesh make_cylinder(int n_around, int n_up, double r, double h) {
  Eigen::MatrixX3d V(n_around * (n_up + 1), 3);
  Eigen::MatrixX3i F(2 * n_around * n_up, 3);
  auto id = [&](int i, int j) { return j * n_around + (i + n_around) % n_around; };
  for (int j = 0; j <= n_up; ++j)
    for (int i = 0; i < n_around; ++i) {
      const double a = 2 * std::numbers::pi * i / n_around;
      V.row(id(i, j)) << r * std::cos(a), r * std::sin(a), h * j / n_up;
    }
  for (int j = 0; j < n_up; ++j)
    for (int i = 0; i < n_around; ++i) {
      const int q = 2 * (j * n_around + i);
      F.row(q) << id(i, j), id(i + 1, j), id(i + 1, j + 1);
      F.row(q + 1) << id(i, j), id(i + 1, j + 1), id(i, j + 1);
    }
  return Mesh::from_triangles(V, F);
}

Mesh make_drilled_plate(int n_around, double r, double side, double thickness) {
  const int n = n_around;
  // vertices: top square ring, top hole ring, bottom square ring, bottom hole ring (k-th at angle 2πk/n)
  Eigen::MatrixX3d V(4 * n, 3);
  const auto ring = [&](int which, int k) { return which * n + (k + n) % n; };
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n, c = std::cos(a), s = std::sin(a);
    const double to_square = 0.5 * side / std::max(std::abs(c), std::abs(s));
    for (int level = 0; level < 2; ++level) {
      const double z = level == 0 ? thickness : 0.0;
      V.row(ring(2 * level, k)) << to_square * c, to_square * s, z;
      V.row(ring(2 * level + 1, k)) << r * c, r * s, z;
    }
  }
  Eigen::MatrixX3i F(8 * n, 3);
  for (int k = 0; k < n; ++k) {
    const int st = ring(0, k), st1 = ring(0, k + 1), ct = ring(1, k), ct1 = ring(1, k + 1);
    const int sb = ring(2, k), sb1 = ring(2, k + 1), cb = ring(3, k), cb1 = ring(3, k + 1);
    F.row(8 * k) << ct, st, st1;  // top, facing +z
    F.row(8 * k + 1) << ct, st1, ct1;
    F.row(8 * k + 2) << cb, sb1, sb;  // bottom, facing −z
    F.row(8 * k + 3) << cb, cb1, sb1;
    F.row(8 * k + 4) << sb, sb1, st1;  // outer wall, facing out
    F.row(8 * k + 5) << sb, st1, st;
    F.row(8 * k + 6) << cb, ct1, cb1;  // hole wall, facing the axis
    F.row(8 * k + 7) << cb, ct, ct1;
  }
  return Mesh::from_triangles(V, F);
}

Mesh make_gear(int teeth, double thickness) {
  const int n = 8 * teeth;
  Eigen::MatrixX3d V(2 * n + 2, 3);  // top outline, bottom outline, top centre, bottom centre
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n, r = (k % 8) >= 2 && (k % 8) < 6 ? 1.0 : 0.8;
    V.row(k) << r * std::cos(a), r * std::sin(a), thickness;
    V.row(n + k) << r * std::cos(a), r * std::sin(a), 0.0;
  }
  V.row(2 * n) << 0, 0, thickness;
  V.row(2 * n + 1) << 0, 0, 0;
  Eigen::MatrixX3i F(4 * n, 3);
  for (int k = 0; k < n; ++k) {
    const int t = k, t1 = (k + 1) % n, b = n + k, b1 = n + (k + 1) % n;
    F.row(4 * k) << 2 * n, t, t1;          // top, facing +z
    F.row(4 * k + 1) << 2 * n + 1, b1, b;  // bottom, facing −z
    F.row(4 * k + 2) << b, b1, t1;         // wall, facing out
    F.row(4 * k + 3) << b, t1, t;
  }
  return Mesh::from_triangles(V, F);
}

Mesh make_ellipsoid(int level, double a, double b, double c) {
  std::vector<Eigen::Vector3d> P = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<Eigen::Vector3i> T = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                    {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int i, int j) {
      const auto key = std::minmax(i, j);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      P.push_back((P[i] + P[j]).normalized());
      return mid[key] = static_cast<int>(P.size()) - 1;
    };
    std::vector<Eigen::Vector3i> next;
    for (const auto& t : T) {
      const int m01 = midpoint(t[0], t[1]), m12 = midpoint(t[1], t[2]), m20 = midpoint(t[2], t[0]);
      next.push_back({t[0], m01, m20});
      next.push_back({m01, t[1], m12});
      next.push_back({m20, m12, t[2]});
      next.push_back({m01, m12, m20});
    }
    T = std::move(next);
  }
  Eigen::MatrixX3d V(P.size(), 3);
  for (std::size_t i = 0; i < P.size(); ++i)
    V.row(static_cast<Eigen::Index>(i)) << a * P[i].x(), b * P[i].y(), c * P[i].z();
  Eigen::MatrixX3i F(T.size(), 3);
  for (std::size_t i = 0; i < T.size(); ++i) F.row(static_cast<Eigen::Index>(i)) = T[i].transpose();
  return Mesh::from_triangles(V, F);
}

Mesh make_torus_and_cylinder() {
  const Mesh torus = make_torus(12, 8), cylinder = make_cylinder(10, 4);
  Eigen::MatrixX3d V(torus.num_vertices() + cylinder.num_vertices(), 3);
  V << torus.V(), cylinder.V();
  Eigen::MatrixX3i F(torus.num_faces() + cylinder.num_faces(), 3);
  F << torus.F(), cylinder.F().array() + torus.num_vertices();
  return Mesh::from_triangles(V, F);
}

Mesh scaled_copies(const Mesh& mesh, const std::vector<double>& scales) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces(), n = static_cast<int>(scales.size());
  const double spacing = 1.5 * (mesh.V().col(0).maxCoeff() - mesh.V().col(0).minCoeff());
  Eigen::MatrixX3d V(n * nv, 3);
  Eigen::MatrixX3i F(n * nf, 3);
  for (int c = 0; c < n; ++c) {
    V.middleRows(c * nv, nv) = scales[c] * mesh.V();
    V.middleRows(c * nv, nv).col(0).array() += spacing * c;
    F.middleRows(c * nf, nf) = mesh.F().array() + c * nv;
  }
  return Mesh::from_triangles(V, F);
}

Mesh with_faces_reversed(const Mesh& mesh) {
  Eigen::MatrixX3i F = mesh.F();
  F.col(1).swap(F.col(2));
  return Mesh::from_triangles(mesh.V(), F);
}

std::vector<int> interior_edges(const Mesh& mesh) {
  std::vector<int> out;
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (!mesh.is_boundary_edge(e)) out.push_back(e);
  return out;
}

}  // namespace quadcover::testing
