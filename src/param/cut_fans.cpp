#include "param/cut_fans.h"

#include <algorithm>

namespace quadcover {

CutFans cut_fans(const Mesh& mesh, const CoverCut& cut) {
  std::vector<char> on_cut(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (cut.graph.cut[e]) on_cut[mesh.E()(e, 0)] = on_cut[mesh.E()(e, 1)] = 1;
  CutFans fans;
  fans.offset.push_back(0);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (!on_cut[v]) continue;
    const int k = static_cast<int>(fans.vertices.size());
    fans.vertices.push_back(v);
    const std::vector<FanCrossing> around = fan_crossings(mesh, v);
    fans.crossings.insert(fans.crossings.end(), around.begin(), around.end());
    fans.offset.push_back(static_cast<int>(fans.crossings.size()));
    const int pe = cut.graph.parent_edge[v];
    if (pe >= 0 && cut.graph.cut[pe]) fans.elimination.push_back(k);
  }
  std::stable_sort(fans.elimination.begin(), fans.elimination.end(), [&](int a, int b) {
    return cut.graph.distance[fans.vertices[a]] > cut.graph.distance[fans.vertices[b]];
  });
  return fans;
}

}  // namespace quadcover
