#include "mesh/vertex_rings.h"

#include <algorithm>
#include <unordered_map>

namespace quadcover {

std::vector<char> grow_vertex_rings(const Mesh& mesh, std::vector<char> in, int rings) {
  for (int k = 0; k < rings; ++k) {
    std::vector<char> next = in;
    for (int f = 0; f < mesh.num_faces(); ++f)
      if (in[mesh.F()(f, 0)] || in[mesh.F()(f, 1)] || in[mesh.F()(f, 2)])
        for (int c = 0; c < 3; ++c) next[mesh.F()(f, c)] = 1;
    in.swap(next);
  }
  return in;
}

std::vector<int> faces_within_rings(const Mesh& mesh, int p, int rings) {
  std::vector<int> vertices{p}, faces;
  std::unordered_map<int, char> seen{{p, 1}};
  for (std::size_t begin = 0, ring = 0; ring < static_cast<std::size_t>(rings); ++ring) {
    const std::size_t end = vertices.size();
    for (std::size_t k = begin; k < end; ++k)
      for (const auto& fc : mesh.fan(vertices[k]))
        for (int c = 0; c < 3; ++c)
          if (seen.emplace(mesh.F()(fc.face, c), 1).second) vertices.push_back(mesh.F()(fc.face, c));
    begin = end;
  }
  for (int q : vertices)
    for (const auto& fc : mesh.fan(q)) faces.push_back(fc.face);
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

}  // namespace quadcover
