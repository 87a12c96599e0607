#include "pipeline/cone_merging.h"

#include <algorithm>
#include <cstdlib>

#include "common/quarter_turn.h"
#include "field/relocation.h"
#include "field/smoothing.h"

namespace quadcover {

std::vector<ConeMerge> coincident_cone_merges(const Mesh& mesh, const Parameterization& map) {
  std::vector<int> quarter(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (const BranchPoint& b : map.branch_points) quarter[b.vertex] = b.quarter_index;
  std::vector<char> used(static_cast<std::size_t>(mesh.num_vertices()), 0);
  std::vector<ConeMerge> merges;
  std::vector<int> faces = map.untangling.stuck_faces;
  std::sort(faces.begin(), faces.end());
  for (const int f : faces) {
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.F()(f, c), b = mesh.F()(f, (c + 1) % 3);
      if (quarter[a] % 4 == 0 || quarter[b] % 4 == 0 || used[a] || used[b]) continue;
      const double gap = std::abs(map.uv(f, c) - map.uv(f, (c + 1) % 3));
      const int e = mesh.FE()(f, (c + 2) % 3);  // corner c to c + 1: the face edge opposite corner c + 2
      if (gap > 1e-9 || e < 0 || mesh.is_boundary_edge(e)) continue;
      const int from = std::max(a, b), into = std::min(a, b);
      merges.push_back({from, into, mod4(quarter[from])});
      used[a] = used[b] = 1;
    }
  }
  return merges;
}

FrameField merge_cones(const Mesh& mesh, const FrameFieldResult& stage, const FrameField& field, double lambda,
                       const std::vector<ConeMerge>& merges) {
  FrameSmoother smoother(mesh, field, stage.stability, stage.trusted, stage.constrained, lambda);
  for (const ConeMerge& m : merges)
    for (const MatchingChange& change : relocation_changes(mesh, {m.from, m.into}, m.quarters))
      smoother.change_matching(change.edge, change.delta);
  return smoother.rotated(smoother.solve());
}

}  // namespace quadcover
