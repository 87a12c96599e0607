#include "mesh/vertex_rings.h"

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

}  // namespace quadcover
