// A seamless map on a midpoint refinement of its mesh (see split_map.h).
#include "pipeline/split_map.h"

#include <unordered_map>

#include "common/quarter_turn.h"
#include "mesh/split_edges.h"

namespace quadcover {

namespace {

/// φ_to = i^rotation φ_from + translation across an edge (4.2.2).
struct Transition {
  int rotation = 0;
  Complex translation = 0;
};

/// The transition of coarse edge e from its face `from` to the other one: the map's (s = EF(e,0) → t = EF(e,1)) or
/// its inverse φ_s = i^{−k} (φ_t − c).
Transition transition_from(const Mesh& mesh, const Parameterization& map, int e, int from) {
  const Transition forward{mod4(map.transition_rotation[e]), map.transition_translation[e]};
  if (from == mesh.EF()(e, 0)) return forward;
  return {mod4(-forward.rotation), -ipow(-forward.rotation) * forward.translation};
}

/// The refinement's bookkeeping: per refined edge its coarse edge (−1 inside a coarse face) and whether its first
/// face lies in the coarse edge's first face.
struct EdgeParents {
  std::vector<int> edge;
  std::vector<char> same_side;
};

EdgeParents edge_parents(const Mesh& coarse, const Mesh& fine, const std::vector<int>& parent_face,
                         const std::vector<int>& edges) {
  const int nv = coarse.num_vertices();
  EdgeParents P{std::vector<int>(static_cast<std::size_t>(fine.num_edges()), -1),
                std::vector<char>(static_cast<std::size_t>(fine.num_edges()), 1)};
  for (int e = 0; e < fine.num_edges(); ++e) {
    const int s = fine.EF()(e, 0), t = fine.EF()(e, 1);
    if (s >= 0 && t >= 0 && parent_face[s] == parent_face[t]) continue;  // a new edge inside a coarse face
    const int a = fine.E()(e, 0), b = fine.E()(e, 1), f = parent_face[s >= 0 ? s : t];
    int parent = a >= nv ? edges[a - nv] : b >= nv ? edges[b - nv] : -1;
    for (int k = 0; k < 3 && parent < 0; ++k)  // both ends coarse vertices: the edge of f opposite its third corner
      if (coarse.F()(f, k) != a && coarse.F()(f, k) != b) parent = coarse.FE()(f, k);
    P.edge[e] = parent;
    P.same_side[e] = s < 0 || parent_face[s] == coarse.EF()(parent, 0);
  }
  return P;
}

/// Frames in the children's bases (the parent's vectors, same plane) and the matching: the identity inside a
/// parent face, the coarse edge's (negated when seen from the other side) on its halves.
FrameField split_field(const Mesh& coarse, const Mesh& fine, const std::vector<int>& parent_face,
                       const EdgeParents& parents, const FrameField& field) {
  FrameField out;
  out.X.resize(fine.num_faces());
  out.Y.resize(fine.num_faces());
  for (int t = 0; t < fine.num_faces(); ++t) {
    const int f = parent_face[t];
    out.X[t] = fine.to_local(t, coarse.to_world(f, field.X[f]));
    out.Y[t] = fine.to_local(t, coarse.to_world(f, field.Y[f]));
  }
  out.matching = Eigen::VectorXi::Zero(fine.num_edges());
  for (int e = 0; e < fine.num_edges(); ++e) {
    const int parent = parents.edge[e];
    if (parent >= 0 && !fine.is_boundary_edge(e))
      out.matching[e] = parents.same_side[e] ? field.matching[parent] : -field.matching[parent];
  }
  return out;
}

/// Transitions and cut flags of the refined edges (identity inside a parent face).
void split_transitions(const Mesh& coarse, const Mesh& fine, const std::vector<int>& parent_face,
                       const EdgeParents& parents, const Parameterization& map, Parameterization& out) {
  const int ne = fine.num_edges();
  out.transition_rotation = Eigen::VectorXi::Zero(ne);
  out.transition_translation = Eigen::VectorXcd::Zero(ne);
  out.cut_edges = Eigen::VectorXi::Zero(ne);
  for (int e = 0; e < ne; ++e) {
    const int parent = parents.edge[e];
    if (parent < 0 || fine.is_boundary_edge(e)) continue;
    const Transition tr = transition_from(coarse, map, parent, parent_face[fine.EF()(e, 0)]);
    out.transition_rotation[e] = tr.rotation;
    out.transition_translation[e] = tr.translation;
    out.cut_edges[e] = map.cut_edges.size() ? map.cut_edges[parent] : 0;
  }
}

/// The layer λ of midpoint m of coarse edge e in the children of coarse face f: 0 in EF(e,0) (or in the only face of
/// a boundary edge), the edge's rotation k_e in EF(e,1), so that i^λ_t = i^k_e i^λ_s holds at m as at e's ends.
int midpoint_layer(const Mesh& coarse, const Parameterization& map, int e, int f) {
  return f == coarse.EF()(e, 1) && coarse.EF()(e, 0) >= 0 ? mod4(map.transition_rotation[e]) : 0;
}

/// Per-corner values and layers of the children: a coarse corner's own, or a midpoint's mean of its edge's ends.
void split_corners(const Mesh& coarse, const Mesh& fine, const std::vector<int>& parent_face,
                   const std::vector<int>& edges, const Parameterization& map, Parameterization& out) {
  const int nv = coarse.num_vertices();
  out.uv.resize(fine.num_faces(), 3);
  out.subspace.layer.resize(fine.num_faces(), 3);
  for (int t = 0; t < fine.num_faces(); ++t) {
    const int f = parent_face[t];
    for (int c = 0; c < 3; ++c) {
      const int v = fine.F()(t, c);
      if (v < nv) {
        const int a = coarse.corner_of(f, v);
        out.uv(t, c) = map.uv(f, a);
        out.subspace.layer(t, c) = map.subspace.layer(f, a);
        continue;
      }
      const int e = edges[v - nv];
      const int a = coarse.corner_of(f, coarse.E()(e, 0)), b = coarse.corner_of(f, coarse.E()(e, 1));
      out.uv(t, c) = 0.5 * (map.uv(f, a) + map.uv(f, b));
      out.subspace.layer(t, c) = midpoint_layer(coarse, map, e, f);
    }
  }
}

/// The face an aligned curve edge's coordinate refers to: EF(e,0), or the only face of a boundary edge.
int curve_face(const Mesh& mesh, int e) { return mesh.face_of_edge(e); }

/// True if the subspace holds coordinate k (0: φ⁰, 1: φ¹) of vertex p in face f: x_p moves φ^{λ mod 2} and y_p
/// moves φ^{λ+1 mod 2} (φ = uv − i^λ (x + iy)).
bool holds_coordinate(const Mesh& mesh, const Parameterization::Subspace& s, int f, int p, int k) {
  if (s.branch[p]) return true;
  const int nv = mesh.num_vertices(), lambda = s.layer(f, mesh.corner_of(f, p));
  return (s.fixed[p] && lambda % 2 == k) || (s.fixed[nv + p] && (lambda + 1) % 2 == k);
}

/// Branch flags and held components: the coarse vertices' as they were; a midpoint holds the coordinate of the
/// enforced curve its edge is on (in the curve face, where its layer is 0: x for φ⁰, y for φ¹) when both ends hold it.
void split_fixed_components(const Mesh& coarse, const Mesh& fine, const std::vector<int>& edges,
                            const Parameterization& map, Parameterization& out) {
  const int nv = coarse.num_vertices(), nv2 = fine.num_vertices();
  out.subspace.branch = Eigen::VectorXi::Zero(nv2);
  out.subspace.branch.head(nv) = map.subspace.branch;
  out.subspace.fixed.assign(static_cast<std::size_t>(2 * nv2), 0);
  for (int p = 0; p < nv; ++p) {
    out.subspace.fixed[p] = map.subspace.fixed[p];
    out.subspace.fixed[nv2 + p] = map.subspace.fixed[nv + p];
  }
  std::vector<int> midpoint(static_cast<std::size_t>(coarse.num_edges()), -1);
  for (std::size_t k = 0; k < edges.size(); ++k) midpoint[edges[k]] = nv + static_cast<int>(k);
  for (const Parameterization::Curve& curve : map.aligned_curves) {
    if (!curve.enforced) continue;
    for (std::size_t j = 0; j < curve.edges.size(); ++j) {
      const int e = curve.edges[j], m = midpoint[e], k = curve.edge_coordinates[j], f = curve_face(coarse, e);
      if (m < 0 || !holds_coordinate(coarse, map.subspace, f, coarse.E()(e, 0), k) ||
          !holds_coordinate(coarse, map.subspace, f, coarse.E()(e, 1), k))
        continue;
      out.subspace.fixed[k == 0 ? m : nv2 + m] = 1;
    }
  }
}

/// The aligned curves on the refined edges: a split edge's two halves, each with its coordinate and integer read in
/// its own curve face (through the coarse edge's transition when that face lies on the other side).
void split_curves(const Mesh& coarse, const Mesh& fine, const std::vector<int>& parent_face,
                  const std::vector<int>& edges, const Parameterization& map, Parameterization& out) {
  const int nv = coarse.num_vertices();
  std::unordered_map<long long, int> fine_edge;
  for (int e = 0; e < fine.num_edges(); ++e)
    fine_edge[static_cast<long long>(fine.E()(e, 0)) * fine.num_vertices() + fine.E()(e, 1)] = e;
  const auto edge_between = [&](int a, int b) {
    return fine_edge.at(static_cast<long long>(std::min(a, b)) * fine.num_vertices() + std::max(a, b));
  };
  std::vector<int> midpoint(static_cast<std::size_t>(coarse.num_edges()), -1);
  for (std::size_t k = 0; k < edges.size(); ++k) midpoint[edges[k]] = nv + static_cast<int>(k);
  for (Parameterization::Curve& curve : out.aligned_curves) {
    Parameterization::Curve refined = curve;
    refined.edges.clear(), refined.edge_coordinates.clear(), refined.edge_values.clear();
    for (std::size_t j = 0; j < curve.edges.size(); ++j) {
      const int e = curve.edges[j], p = coarse.E()(e, 0), q = coarse.E()(e, 1), m = midpoint[e];
      const int from = curve_face(coarse, e);
      std::vector<int> pieces = m < 0 ? std::vector<int>{edge_between(p, q)}
                                      : std::vector<int>{edge_between(p, m), edge_between(m, q)};
      for (int piece : pieces) {
        int k = curve.edge_coordinates[j];
        double value = curve.edge_values[j];
        if (parent_face[curve_face(fine, piece)] != from) {  // the line {φ^k = value} seen through the transition
          const Transition tr = transition_from(coarse, map, e, from);
          const Complex w = ipow(tr.rotation) * (k == 0 ? Complex(value, 0) : Complex(0, value)) + tr.translation;
          k = (k + tr.rotation) % 2;
          value = k == 0 ? w.real() : w.imag();
        }
        refined.edges.push_back(piece);
        refined.edge_coordinates.push_back(k);
        refined.edge_values.push_back(value);
      }
    }
    curve = std::move(refined);
  }
}

}  // namespace

SplitMap split_map(const Mesh& mesh, const FrameField& field, const Parameterization& map,
                   const std::vector<int>& edges) {
  SplitMesh split = split_edges_at_midpoints(mesh, edges);
  SplitMap out{Mesh::from_triangles(split.V, split.F), {}, map, std::move(split.parent_face), {}};
  for (int e : edges) out.split.push_back({mesh.E()(e, 0), mesh.E()(e, 1)});
  const Mesh& fine = out.mesh;
  const EdgeParents parents = edge_parents(mesh, fine, out.parent_face, edges);
  out.field = split_field(mesh, fine, out.parent_face, parents, field);
  Parameterization& P = out.map;
  split_corners(mesh, fine, out.parent_face, edges, map, P);
  split_transitions(mesh, fine, out.parent_face, parents, map, P);
  split_fixed_components(mesh, fine, edges, map, P);
  split_curves(mesh, fine, out.parent_face, edges, map, P);
  P.face_rotation.resize(fine.num_faces());
  for (int t = 0; t < fine.num_faces(); ++t) P.face_rotation[t] = map.face_rotation[out.parent_face[t]];
  return out;
}

}  // namespace quadcover
