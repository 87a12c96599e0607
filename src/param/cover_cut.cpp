// Cut graph through B = branch points ∪ boundary (thesis 4.2) and the disk gauge of the covering.
#include "param/cover_cut.h"

#include <algorithm>

#include "common/errors.h"
#include "common/quarter_turn.h"
#include "field/indices.h"

namespace quadcover {

std::vector<FanCrossing> fan_crossings(const Mesh& mesh, int v) {
  const auto fan = mesh.fan(v);
  const int d = static_cast<int>(fan.size());
  std::vector<FanCrossing> out;
  const int steps = mesh.is_boundary_vertex(v) ? d - 1 : d;
  out.reserve(static_cast<std::size_t>(std::max(steps, 0)));
  for (int i = 0; i < steps; ++i) {
    const int f = fan[i].face, g = fan[(i + 1) % d].face;
    for (int k = 0; k < 3; ++k) {
      const int e = mesh.FE()(f, k);
      if (mesh.neighbor(f, k) == g && (mesh.E()(e, 0) == v || mesh.E()(e, 1) == v)) {
        out.push_back({f, g, e});
        break;
      }
    }
  }
  return out;
}

int CoverCut::h_sym() const {
  int dep = 0;
  for (int j : dependent_path) dep += j >= 0;
  return 2 * (num_paths() - dep);
}

int symmetric_period_count(int genus, int b_even, int b_odd, int boundary_loops) {
  // n = 2g + b + L - 1 paths (Algorithm 1.16 with base set B and L boundary loops; a closed surface without base
  // vertices gets one root: n = 2g); with branch points one path is fixed by the constant of φ.
  const int b = b_even + b_odd;
  if (b == 0) return boundary_loops == 0 ? 4 * genus : 2 * (2 * genus + boundary_loops - 1);
  return 4 * genus + 2 * (b + boundary_loops) - 4;  // (4.1) for L = 0
}

CoverCut build_cover_cut(const Mesh& mesh, const Eigen::VectorXi& matching) {
  if (matching.size() != mesh.num_edges())
    throw InputError("", 0, "parameterize: the matching has the wrong number of edges");
  CoverCut cc;
  cc.quarter_index = matching_quarter_index(mesh, matching);
  cc.branch = Eigen::VectorXi::Zero(mesh.num_vertices());
  std::vector<int> base;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const int r = mod4(cc.quarter_index[v]);
    if (r == 0) continue;
    cc.branch[v] = 1;
    base.push_back(v);
    (r == 2 ? cc.b_even : cc.b_odd) += 1;
  }
  cc.graph = cut_graph(mesh, base);
  cc.disk = cut_mesh(mesh, cc.graph.cut);

  // Gauge: breadth-first over faces through uncut interior edges, r_t = r_s + m_e (so m'_e = m_e + r_s - r_t = 0).
  const int nf = mesh.num_faces();
  cc.face_rotation = Eigen::VectorXi::Constant(nf, -1);
  std::vector<int> queue;
  for (int root = 0; root < nf; ++root) {
    if (cc.face_rotation[root] >= 0) continue;
    cc.face_rotation[root] = 0;
    queue.assign(1, root);
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int f = queue[q];
      for (int k = 0; k < 3; ++k) {
        const int e = mesh.FE()(f, k), g = mesh.neighbor(f, k);
        if (g < 0 || cc.graph.cut[e] || cc.face_rotation[g] >= 0) continue;
        cc.face_rotation[g] = mod4(mesh.EF()(e, 0) == f ? cc.face_rotation[f] + matching[e]
                                                         : cc.face_rotation[f] - matching[e]);
        queue.push_back(g);
      }
    }
  }
  cc.matching = matching;
  cc.rotation = Eigen::VectorXi::Zero(mesh.num_edges());
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    if (s < 0 || t < 0) continue;
    cc.matching[e] = matching[e] + cc.face_rotation[s] - cc.face_rotation[t];
    if (cc.graph.cut[e]) {
      cc.rotation[e] = mod4(-cc.matching[e]);
    } else if (mod4(cc.matching[e]) != 0) {
      throw NumericalError("parameterize", "the disk gauge does not close at edge " + std::to_string(e) +
                                               ": a vertex inside the cut disk has a non-integer index");
    }
  }

  // Paths, their components, and the dependent path per component (4.2: n - 1 of the n paths are used).
  const int nc = mesh.num_components();
  cc.dependent_path.assign(static_cast<std::size_t>(nc), -1);
  for (const CutPath& p : cc.graph.paths) {
    const int e = p.leftover_edge;
    const int j = static_cast<int>(cc.path_edge.size());
    cc.path_edge.push_back(e);
    const int c = mesh.face_component()[mesh.EF()(e, 0)];
    cc.path_component.push_back(c);
    const int k = cc.rotation[e];
    int& dep = cc.dependent_path[c];
    // Prefer an odd rotation (1 - i^k invertible with a unit quotient), then the lowest index.
    if (k != 0 && (dep < 0 || (cc.rotation[cc.path_edge[dep]] == 2 && k != 2))) dep = j;
  }
  return cc;
}

}  // namespace quadcover
