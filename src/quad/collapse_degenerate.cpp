#include "quad/collapse_degenerate.h"

#include <algorithm>
#include <exception>

#include "common/quarter_turn.h"
#include "quad/integer_grid_map.h"
#include "quad/transitions.h"

namespace quadcover {

namespace {

// φ_g = i^r φ_f + c: the chart change from face f to face g.
struct Change {
  int r = 0;
  Complex c{0, 0};
  Change then(const Change& next) const { return {(r + next.r) & 3, ipow(next.r) * c + next.c}; }  // next ∘ this
};

// The chart change across the shared edge of adjacent faces f -> g (thesis 4.2.2 convention of Parameterization).
Change across(const Mesh& mesh, const Parameterization& p, int f, int g) {
  for (int k = 0; k < 3; ++k) {
    if (mesh.neighbor(f, k) != g) continue;
    const int e = mesh.FE()(f, k);
    const int r = p.transition_rotation.size() ? mod4(p.transition_rotation[e]) : 0;
    const Complex c = p.transition_translation.size() ? p.transition_translation[e] : Complex(0, 0);
    if (mesh.EF()(e, 0) == f) return {r, c};
    return {(4 - r) & 3, -(ipow(-r) * c)};  // φ_s = i^{-r}(φ_t − c)
  }
  return {-1, {0, 0}};
}

std::vector<int> one_ring(const Mesh& mesh, int v) {
  std::vector<int> ring;
  for (const auto& fc : mesh.fan(v))
    for (int c = 0; c < 3; ++c)
      if (mesh.F()(fc.face, c) != v) ring.push_back(mesh.F()(fc.face, c));
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  return ring;
}

// The edges of one pass: an independent set of interior edges of zero length in the map (within tol) whose collapse
// keeps a manifold (link condition, no boundary vertex). merge_into[b] = a for each, and the two triangles of the
// edge are marked removed (also listed in removed_list). \return the number of edges.
int choose_collapses(const Mesh& mesh, const Parameterization& param, double tol, std::vector<int>& merge_into,
                     std::vector<char>& removed, std::vector<int>& removed_list) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  std::vector<char> locked(nv, 0);
  removed.assign(nf, 0);
  merge_into.assign(nv, -1);
  int count = 0;
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    if (s < 0 || t < 0) continue;
    const int a = mesh.E()(e, 0), b = mesh.E()(e, 1);
    const int ca = grid::local_corner(mesh, s, a), cb = grid::local_corner(mesh, s, b);
    if (std::abs(param.uv(s, ca) - param.uv(s, cb)) > tol) continue;
    // Two vertices a micro-unit apart under triangles the map keeps positive are not one point (the grid map keeps
    // them apart), unless both sit on a lattice point, where the snapping joins them.
    const bool on_lattice =
        grid::at_lattice_point(param.uv(s, ca), tol / 2) && grid::at_lattice_point(param.uv(s, cb), tol / 2);
    if (!on_lattice && grid::positive_in_map(param.uv.row(s)) && grid::positive_in_map(param.uv.row(t))) continue;
    const int c = mesh.F()(s, 3 - ca - cb),
              d = mesh.F()(t, 3 - grid::local_corner(mesh, t, a) - grid::local_corner(mesh, t, b));
    if (locked[a] || locked[b] || locked[c] || locked[d] || c == d) continue;
    if (mesh.is_boundary_vertex(a) || mesh.is_boundary_vertex(b)) continue;
    // link condition: the common neighbours of a and b are exactly c and d
    const std::vector<int> ra = one_ring(mesh, a), rb = one_ring(mesh, b);
    std::vector<int> common;
    std::set_intersection(ra.begin(), ra.end(), rb.begin(), rb.end(), std::back_inserter(common));
    if (common.size() != 2) continue;
    if (ra.size() <= 3 || rb.size() <= 3) continue;  // a tetrahedron-like cap would fold onto itself
    locked[a] = locked[b] = locked[c] = locked[d] = 1;
    merge_into[b] = a;
    removed[s] = removed[t] = 1;
    removed_list.push_back(s);
    removed_list.push_back(t);
    ++count;
  }
  return count;
}

// The collapsed triangles: b merged into a at the midpoint (3D), vertices compacted; the kept faces (old indices in
// `kept`) with their corner uv.
void collapsed_geometry(const Mesh& mesh, const Parameterization& param, const std::vector<int>& merge_into,
                        const std::vector<char>& removed, Eigen::MatrixX3d& V, Eigen::MatrixX3i& F,
                        Eigen::MatrixX3cd& uv, std::vector<int>& kept) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  std::vector<int> new_id(nv, -1);
  int n2 = 0;
  for (int v = 0; v < nv; ++v)
    if (merge_into[v] < 0) new_id[v] = n2++;
  for (int v = 0; v < nv; ++v)
    if (merge_into[v] >= 0) new_id[v] = new_id[merge_into[v]];
  V.resize(n2, 3);
  for (int v = 0; v < nv; ++v)
    if (merge_into[v] < 0) V.row(new_id[v]) = mesh.V().row(v);
  for (int v = 0; v < nv; ++v)
    if (merge_into[v] >= 0) V.row(new_id[v]) = 0.5 * (mesh.V().row(v) + mesh.V().row(merge_into[v]));
  for (int f = 0; f < nf; ++f)
    if (!removed[f]) kept.push_back(f);
  F.resize(static_cast<Eigen::Index>(kept.size()), 3);
  uv.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      F(i, c) = new_id[mesh.F()(kept[i], c)];
      uv(i, c) = param.uv(kept[i], c);
    }
}

// Transitions of the edges of the collapsed mesh m2: the old one between the same faces, or composed through a
// removed triangle. false if an adjacency has neither (not expected).
bool collapsed_transitions(const Mesh& mesh, const Parameterization& param, const Mesh& m2,
                           const std::vector<int>& kept, const std::vector<int>& removed_list, Parameterization& p2) {
  p2.transition_rotation = Eigen::VectorXi::Zero(m2.num_edges());
  p2.transition_translation = Eigen::VectorXcd::Zero(m2.num_edges());
  p2.cut_edges = Eigen::VectorXi::Zero(m2.num_edges());
  for (int e = 0; e < m2.num_edges(); ++e) {
    const int s2 = m2.EF()(e, 0), t2 = m2.EF()(e, 1);
    if (s2 < 0 || t2 < 0) continue;
    const int s = kept[s2], t = kept[t2];
    Change ch = across(mesh, param, s, t);
    for (std::size_t i = 0; i < removed_list.size() && ch.r < 0; ++i) {
      const int d = removed_list[i];
      const Change c1 = across(mesh, param, s, d), c2 = across(mesh, param, d, t);
      if (c1.r >= 0 && c2.r >= 0) ch = c1.then(c2);
    }
    if (ch.r < 0) return false;  // not expected: every new adjacency comes from one of the two cases
    p2.transition_rotation[e] = ch.r;
    p2.transition_translation[e] = ch.c;
    p2.cut_edges[e] = ch.r != 0 || std::abs(ch.c) > 0;
  }
  return true;
}

// One pass: an independent set of collapsible edges, rebuilt into a new mesh. false if nothing was collapsed.
bool collapse_pass(const Mesh& mesh, const Parameterization& param, double tol, const std::vector<int>& origin_in,
                   CollapsedMap& out) {
  std::vector<int> merge_into, removed_list;
  std::vector<char> removed;
  const int count = choose_collapses(mesh, param, tol, merge_into, removed, removed_list);
  if (count == 0) return false;
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  Eigen::MatrixX3cd uv;
  std::vector<int> kept;
  collapsed_geometry(mesh, param, merge_into, removed, V, F, uv, kept);
  Mesh m2;
  try {
    m2 = Mesh::from_triangles(V, F);
  } catch (const std::exception&) {
    return false;  // the collapse would not give a valid mesh: keep the input (its degenerate triangles are cut out)
  }
  if (m2.num_faces() != F.rows() || !(m2.F() == F)) return false;
  Parameterization p2;
  p2.uv = uv;
  if (!collapsed_transitions(mesh, param, m2, kept, removed_list, p2)) return false;
  out.face_origin.resize(kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) out.face_origin[i] = origin_in[kept[i]];
  out.mesh = std::move(m2);
  out.param = std::move(p2);
  out.collapsed_edges += count;
  return true;
}

}  // namespace

CollapsedMap collapse_zero_edges(const Mesh& mesh, const Parameterization& param, double tol, int max_passes) {
  CollapsedMap out;
  std::vector<int> origin(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) origin[f] = f;
  if (!collapse_pass(mesh, param, tol, origin, out)) return out;
  for (int pass = 1; pass < max_passes; ++pass) {
    CollapsedMap next;
    next.collapsed_edges = out.collapsed_edges;
    if (!collapse_pass(out.mesh, out.param, tol, out.face_origin, next)) break;
    out = std::move(next);
  }
  return out;
}

}  // namespace quadcover
