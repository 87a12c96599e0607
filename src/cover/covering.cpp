// The explicit 4-sheeted covering of a matching (thesis 3.2.2) and its real stiffness matrix (3.7).
#include "cover/covering.h"

#include <algorithm>
#include <map>

#include "common/errors.h"
#include "common/quarter_turn.h"
#include "common/union_find.h"

namespace quadcover {

namespace {

/// Layer of the copy of the other face glued to layer l of face f across interior edge e: t̃_s^k ~ t̃_t^{k - m_e}.
int glued_layer(const Mesh& mesh, const Eigen::VectorXi& m, int e, int f, int l) {
  return mod4(mesh.EF()(e, 0) == f ? l - m[e] : l + m[e]);
}

}  // namespace

std::vector<int> Covering::genus() const {
  std::vector<int> g(euler_characteristic.size());
  for (std::size_t c = 0; c < g.size(); ++c) g[c] = (2 - euler_characteristic[c] - boundary_loops[c]) / 2;
  return g;
}

namespace {

/// Edges (3.5): the copy of e adjoining layer l of f has the layer of the adjoining reference-face copy.
void glue_edges(const Mesh& mesh, const Eigen::VectorXi& m, Covering& cov) {
  cov.FE.resize(4 * mesh.num_faces(), 3);
  cov.num_edges = 4 * mesh.num_edges();
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int e = mesh.FE()(f, k);
      const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
      const int ref = s < 0 ? t : (t < 0 ? s : std::min(s, t));
      for (int l = 0; l < 4; ++l) cov.FE(4 * f + l, k) = 4 * e + (ref == f ? l : glued_layer(mesh, m, e, f, l));
    }
}

/// Vertices: corners glued across covering edges, one class per cycle of faces (3.2.2), numbered in order of first
/// corner; the layer of a covering vertex is that of its lowest-index base face.
void glue_vertices(const Mesh& mesh, const Eigen::VectorXi& m, Covering& cov) {
  const int nf = mesh.num_faces();
  detail::UnionFind corners(12 * nf);
  auto slot = [](int f, int l, int c) { return 3 * (4 * f + l) + c; };
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    if (s < 0 || t < 0) continue;
    for (int l = 0; l < 4; ++l) {
      const int lt = glued_layer(mesh, m, e, s, l);
      for (int end = 0; end < 2; ++end) {
        const int v = mesh.E()(e, end);
        corners.unite(slot(s, l, mesh.corner_of(s, v)), slot(t, lt, mesh.corner_of(t, v)));
      }
    }
  }
  std::map<int, int> id;
  cov.F.resize(4 * nf, 3);
  std::vector<std::pair<int, int>> best;  // (base face, layer) per covering vertex
  for (int f = 0; f < nf; ++f)
    for (int l = 0; l < 4; ++l)
      for (int c = 0; c < 3; ++c) {
        const int root = corners.find(slot(f, l, c));
        auto [it, inserted] = id.try_emplace(root, cov.num_vertices());
        if (inserted) {
          cov.base_vertex.push_back(mesh.F()(f, c));
          best.emplace_back(f, l);
        } else {
          best[it->second] = std::min(best[it->second], std::make_pair(f, l));
        }
        cov.F(4 * f + l, c) = it->second;
      }
  cov.layer.resize(best.size());
  for (std::size_t i = 0; i < best.size(); ++i) cov.layer[i] = best[i].second;
}

/// Components through covering edges, and per component χ = v − e + f (1.1) and the boundary loops (cycles of
/// boundary covering edges joined at their covering vertices).
void count_components(Covering& cov) {
  const int nF = cov.num_faces();
  detail::UnionFind faces(nF);
  std::vector<int> edge_face(static_cast<std::size_t>(cov.num_edges), -1), edge_count(cov.num_edges, 0);
  for (int F = 0; F < nF; ++F)
    for (int k = 0; k < 3; ++k) {
      const int E = cov.FE(F, k);
      if (edge_face[E] >= 0) faces.unite(edge_face[E], F);
      edge_face[E] = F;
      ++edge_count[E];
    }
  std::map<int, int> comp;
  cov.face_component.resize(nF);
  for (int F = 0; F < nF; ++F) {
    auto [it, inserted] = comp.try_emplace(faces.find(F), static_cast<int>(comp.size()));
    cov.face_component[F] = it->second;
  }
  cov.num_components = static_cast<int>(comp.size());
  std::vector<int> nv(cov.num_components, 0), ne(cov.num_components, 0), nfc(cov.num_components, 0);
  std::vector<int> vertex_comp(static_cast<std::size_t>(cov.num_vertices()), -1);
  for (int F = 0; F < nF; ++F) {
    ++nfc[cov.face_component[F]];
    for (int c = 0; c < 3; ++c) vertex_comp[cov.F(F, c)] = cov.face_component[F];
  }
  for (int v = 0; v < cov.num_vertices(); ++v) ++nv[vertex_comp[v]];
  for (int E = 0; E < cov.num_edges; ++E) ++ne[cov.face_component[edge_face[E]]];
  detail::UnionFind bverts(cov.num_vertices());
  std::vector<char> on_boundary(static_cast<std::size_t>(cov.num_vertices()), 0);
  for (int F = 0; F < nF; ++F)
    for (int k = 0; k < 3; ++k)
      if (edge_count[cov.FE(F, k)] == 1) {
        const int a = cov.F(F, (k + 1) % 3), b = cov.F(F, (k + 2) % 3);
        bverts.unite(a, b);
        on_boundary[a] = on_boundary[b] = 1;
      }
  cov.boundary_loops.assign(cov.num_components, 0);
  for (int v = 0; v < cov.num_vertices(); ++v)
    if (on_boundary[v] && bverts.find(v) == v) ++cov.boundary_loops[vertex_comp[v]];
  cov.euler_characteristic.resize(cov.num_components);
  for (int c = 0; c < cov.num_components; ++c) cov.euler_characteristic[c] = nv[c] - ne[c] + nfc[c];
}

}  // namespace

Covering build_covering(const Mesh& mesh, const Eigen::VectorXi& m) {
  if (m.size() != mesh.num_edges()) throw InputError("", 0, "build_covering: matching size differs from #E");
  Covering cov;
  glue_edges(mesh, m, cov);
  glue_vertices(mesh, m, cov);
  count_components(cov);
  return cov;
}

Eigen::MatrixX3d covering_positions(const Mesh& mesh, const Covering& covering) {
  Eigen::MatrixX3d P(covering.num_vertices(), 3);
  for (int v = 0; v < covering.num_vertices(); ++v) P.row(v) = mesh.V().row(covering.base_vertex[v]);
  return P;
}

Eigen::SparseMatrix<double> covering_nonconforming_stiffness(const Mesh& mesh, const Covering& covering) {
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(9 * covering.num_faces()));
  for (int F = 0; F < covering.num_faces(); ++F) {
    const int f = F / 4;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        // (3.7): the geometry of t̃^l is that of t, so its element matrix is that of 𝔏* (1.5).
        const double K = std::real(std::conj(mesh.edge_vector_local(f, a)) * mesh.edge_vector_local(f, b)) /
                         mesh.face_areas()[f];
        trip.emplace_back(covering.FE(F, a), covering.FE(F, b), K);
      }
  }
  Eigen::SparseMatrix<double> L(covering.num_edges, covering.num_edges);
  L.setFromTriplets(trip.begin(), trip.end());
  return L;
}

int expected_covering_genus(int genus, int b_even, int b_odd) {
  // χ̃ = 4χ - 3 b_odd - 2 b_even, g̃ = 1 - χ̃/2 (Riemann–Hurwitz, Lemma 3.5 (4)).
  return 4 * genus + b_even + (3 * b_odd) / 2 - 3;
}

}  // namespace quadcover
