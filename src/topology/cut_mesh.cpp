#include "topology/cut_mesh.h"

#include <string>

#include "common/errors.h"
#include "common/union_find.h"

namespace quadcover {

namespace {

/// Whether edge e separates the faces on its two sides in the cut mesh: a cut or a boundary edge.
struct Separates {
  const Mesh& mesh;
  const Eigen::VectorXi& cut;
  bool operator()(int e) const { return cut[e] != 0 || mesh.is_boundary_edge(e); }
};

/// One cut-vertex per wedge of each vertex's fan between separating edges: corner_vertex, original_vertex.
void split_vertices(const Mesh& mesh, const Separates& separates, CutMesh& result) {
  result.corner_vertex = Eigen::MatrixX3i::Constant(mesh.num_faces(), 3, -1);
  result.original_vertex.reserve(static_cast<std::size_t>(mesh.num_vertices()));
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const auto fan = mesh.fan(v);
    const int n = static_cast<int>(fan.size());
    // The edge after fan[i] (counter-clockwise) is {v, corner i+2 of fan[i]}: face edge (corner + 1) % 3.
    auto edge_after = [&](int i) { return mesh.FE()(fan[i].face, (fan[i].corner + 1) % 3); };
    // A wedge starts at fan[0] for boundary vertices, else after the first separating edge (if any).
    int start = 0;
    if (!mesh.is_boundary_vertex(v)) {
      for (int i = 0; i < n; ++i)
        if (separates(edge_after(i))) {
          start = (i + 1) % n;
          break;
        }
    }
    int current = -1;
    for (int j = 0; j < n; ++j) {
      const int i = (start + j) % n;
      if (current < 0) {
        current = static_cast<int>(result.original_vertex.size());
        result.original_vertex.push_back(v);
      }
      result.corner_vertex(fan[i].face, fan[i].corner) = current;
      if (separates(edge_after(i))) current = -1;
    }
  }
}

/// The boundary loops of the cut mesh, each a cycle of boundary half-edges. Boundary half-edges leave corner c
/// towards corner c+1 along face edge (c+2) % 3. \throw TopologyError if they do not form closed loops.
void trace_boundary_loops(const Mesh& mesh, const Separates& separates, CutMesh& result) {
  const int ncv = result.num_vertices();
  std::vector<Mesh::FanCorner> outgoing(static_cast<std::size_t>(ncv), Mesh::FanCorner{-1, -1});
  std::vector<int> order;  // cut-vertices with an outgoing boundary half-edge, in discovery order
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c)
      if (separates(mesh.FE()(f, (c + 2) % 3))) {
        const int from = result.corner_vertex(f, c);
        if (outgoing[from].face >= 0)
          throw TopologyError("cut_mesh: cut-vertex " + std::to_string(from) + " of vertex " +
                              std::to_string(result.original_vertex[from]) + " has two outgoing boundary half-edges");
        outgoing[from] = {f, c};
        order.push_back(from);
      }
  std::vector<char> visited(static_cast<std::size_t>(ncv), 0);
  for (const int s : order) {
    if (visited[s]) continue;
    std::vector<Mesh::FanCorner> loop;
    for (int x = s; !visited[x];) {
      visited[x] = 1;
      const Mesh::FanCorner h = outgoing[x];
      if (h.face < 0)
        throw TopologyError("cut_mesh: boundary of the cut mesh is not closed at vertex " +
                            std::to_string(result.original_vertex[x]));
      loop.push_back(h);
      x = result.corner_vertex(h.face, (h.corner + 1) % 3);
    }
    result.boundary_loops.push_back(std::move(loop));
  }
}

/// Faces joined across edges that do not separate: face_piece, num_pieces (numbered by lowest face).
void label_pieces(const Mesh& mesh, const Separates& separates, CutMesh& result) {
  const int nf = mesh.num_faces();
  detail::UnionFind pieces(nf);
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (!separates(e)) pieces.unite(mesh.EF()(e, 0), mesh.EF()(e, 1));
  result.face_piece = Eigen::VectorXi::Constant(nf, -1);
  std::vector<int> label(static_cast<std::size_t>(nf), -1);
  for (int f = 0; f < nf; ++f) {
    const int r = pieces.find(f);
    if (label[r] < 0) label[r] = result.num_pieces++;
    result.face_piece[f] = label[r];
  }
}

}  // namespace

CutMesh cut_mesh(const Mesh& mesh, const Eigen::VectorXi& cut) {
  const int ne = mesh.num_edges();
  if (cut.size() != ne)
    throw InputError("", 0,
                     "cut_mesh: " + std::to_string(cut.size()) + " cut flags for " + std::to_string(ne) + " edges");
  const Separates separates{mesh, cut};
  CutMesh result;
  split_vertices(mesh, separates, result);
  result.num_edges = ne;
  for (int e = 0; e < ne; ++e)
    if (cut[e] != 0 && !mesh.is_boundary_edge(e)) ++result.num_edges;
  trace_boundary_loops(mesh, separates, result);
  label_pieces(mesh, separates, result);
  return result;
}

}  // namespace quadcover
