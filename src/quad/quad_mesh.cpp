#include "quad/quad_mesh.h"

#include <algorithm>
#include <vector>

namespace quadcover {

int QuadMesh::num_quads() const {
  return static_cast<int>(std::count_if(faces.begin(), faces.end(), [](const auto& f) { return f.size() == 4; }));
}

std::vector<std::pair<std::pair<int, int>, int>> polygon_edge_uses(const std::vector<std::vector<int>>& faces) {
  std::vector<std::pair<int, int>> sides;  // undirected, sorted: equal edges are adjacent
  for (const auto& f : faces)
    for (std::size_t k = 0; k < f.size(); ++k) sides.push_back(std::minmax(f[k], f[(k + 1) % f.size()]));
  std::sort(sides.begin(), sides.end());
  std::vector<std::pair<std::pair<int, int>, int>> uses;
  for (std::size_t i = 0, j = 0; i < sides.size(); i = j) {
    while (j < sides.size() && sides[j] == sides[i]) ++j;
    uses.push_back({sides[i], static_cast<int>(j - i)});
  }
  return uses;
}

std::vector<char> quad_boundary_vertices(const QuadMesh& q) {
  std::vector<char> on_boundary(static_cast<std::size_t>(q.num_vertices()), 0);
  for (const auto& [e, n] : polygon_edge_uses(q.faces))
    if (n == 1) on_boundary[e.first] = on_boundary[e.second] = 1;
  return on_boundary;
}

// polygon mesh would then be non-manifold. Keep the smallest face on such an edge and drop the others.
int drop_faces_on_duplicate_edges(QuadMesh& qm) {
  // (directed edge, face) for every face side, sorted: equal edges are adjacent (no per-edge allocation).
  std::vector<std::pair<unsigned long long, int>> sides;
  std::size_t total = 0;
  for (const auto& F : qm.faces) total += F.size();
  sides.reserve(total);
  for (int f = 0; f < qm.num_faces(); ++f) {
    const auto& F = qm.faces[f];
    for (std::size_t i = 0; i < F.size(); ++i)
      sides.emplace_back((static_cast<unsigned long long>(static_cast<unsigned>(F[i])) << 32) |
                             static_cast<unsigned>(F[(i + 1) % F.size()]),
                         f);
  }
  std::sort(sides.begin(), sides.end());
  std::vector<char> drop(qm.num_faces(), 0);
  auto smaller = [&](int a, int b) {
    return qm.faces[a].size() != qm.faces[b].size() ? qm.faces[a].size() < qm.faces[b].size() : a < b;
  };
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i + 1;
    while (j < sides.size() && sides[j].first == sides[i].first) ++j;
    if (j - i > 1) {
      int keep = sides[i].second;
      for (std::size_t k = i + 1; k < j; ++k)
        if (smaller(sides[k].second, keep)) keep = sides[k].second;
      for (std::size_t k = i; k < j; ++k)
        if (sides[k].second != keep) drop[sides[k].second] = 1;
    }
    i = j;
  }
  int dropped = 0;
  std::vector<std::vector<int>> kept;
  kept.reserve(qm.faces.size());
  for (int f = 0; f < qm.num_faces(); ++f)
    if (drop[f])
      ++dropped;
    else
      kept.push_back(std::move(qm.faces[f]));
  qm.faces = std::move(kept);
  return dropped;
}

// Where cut-out folds touch at one output vertex its faces form several fans: give each fan its own copy so that
// the output stays a manifold polygon mesh.
int split_pinched_vertices(QuadMesh& qm) {
  const int nv = qm.num_vertices();
  std::vector<std::vector<std::pair<int, int>>> corners(nv);  // (face, index in face)
  for (int f = 0; f < qm.num_faces(); ++f)
    for (int i = 0; i < static_cast<int>(qm.faces[f].size()); ++i) corners[qm.faces[f][i]].emplace_back(f, i);
  std::vector<std::vector<int>> extra_of(nv);
  int added = 0;
  for (int v = 0; v < nv; ++v) {
    const auto& cs = corners[v];
    const int m = static_cast<int>(cs.size());
    if (m < 2) continue;
    std::vector<int> parent(m);
    for (int i = 0; i < m; ++i) parent[i] = i;
    auto find = [&](int i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    auto nbr = [&](int i, int step) {
      const auto& f = qm.faces[cs[i].first];
      const int n = static_cast<int>(f.size());
      return f[(cs[i].second + step + n) % n];
    };
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j)
        if (i != j && nbr(i, 1) == nbr(j, -1)) parent[find(i)] = find(j);
    std::vector<int> roots;
    for (int i = 0; i < m; ++i)
      if (find(i) == i) roots.push_back(i);
    for (std::size_t r = 1; r < roots.size(); ++r) {
      const int nvid = nv + added++;
      extra_of[v].push_back(nvid);
      for (int i = 0; i < m; ++i)
        if (find(i) == roots[r]) qm.faces[cs[i].first][cs[i].second] = nvid;
    }
  }
  if (added == 0) return 0;
  qm.V.conservativeResize(nv + added, 3);
  qm.uv.conservativeResize(nv + added);
  qm.source_face.conservativeResize(nv + added);
  qm.on_grid.conservativeResize(nv + added);
  for (int v = 0; v < nv; ++v)
    for (int c : extra_of[v]) {
      qm.V.row(c) = qm.V.row(v);
      qm.uv[c] = qm.uv[v];
      qm.source_face[c] = qm.source_face[v];
      qm.on_grid[c] = qm.on_grid[v];
    }
  return added;
}

int remove_spikes(std::vector<int>& loop) {
  int removed = 0;
  for (bool again = true; again && loop.size() >= 3;) {
    again = false;
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i)
      if (loop[(i + n - 1) % n] == loop[(i + 1) % n]) {  // drop v = loop[i] and the second x = loop[i + 1]
        std::vector<int> kept;
        for (std::size_t j = 0; j < n; ++j)
          if (j != i && j != (i + 1) % n) kept.push_back(loop[j]);
        loop.swap(kept);
        ++removed;
        again = true;
        break;
      }
  }
  return removed;
}

int remove_unused_vertices(QuadMesh& qm) {
  const int nv = qm.num_vertices();
  std::vector<int> remap(nv, -1);
  int used = 0;
  for (auto& f : qm.faces)
    for (int& v : f) {
      if (remap[v] < 0) remap[v] = used++;
      v = remap[v];
    }
  QuadMesh out;
  out.V.resize(used, 3);
  out.uv.resize(qm.uv.size() == nv ? used : 0);  // per-vertex arrays that are not #V are dropped
  out.source_face.resize(qm.source_face.size() == nv ? used : 0);
  out.on_grid.resize(qm.on_grid.size() == nv ? used : 0);
  for (int v = 0; v < nv; ++v) {
    const int r = remap[v];
    if (r < 0) continue;
    out.V.row(r) = qm.V.row(v);
    if (qm.uv.size() == nv) out.uv[r] = qm.uv[v];
    if (qm.source_face.size() == nv) out.source_face[r] = qm.source_face[v];
    if (qm.on_grid.size() == nv) out.on_grid[r] = qm.on_grid[v];
  }
  qm.V = std::move(out.V);
  qm.uv = std::move(out.uv);
  qm.source_face = std::move(out.source_face);
  qm.on_grid = std::move(out.on_grid);
  return nv - used;
}

}  // namespace quadcover
