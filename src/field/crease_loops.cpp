#include "field/crease_loops.h"

#include <cmath>
#include <numbers>

namespace quadcover {

namespace {

constexpr double kPi = std::numbers::pi;

/// The loop through sharp edge `first` (from its vertex 0), or an empty loop when the curve through it is not closed
/// or meets a vertex of another number of sharp edges. Marks the edges walked in `walked`.
CreaseLoop trace_loop(const Mesh& mesh, const std::vector<std::vector<int>>& sharp_at, int first,
                      std::vector<char>& walked) {
  CreaseLoop loop;
  loop.vertices.push_back(mesh.E()(first, 0));
  loop.edges.push_back(first);
  walked[first] = 1;
  int v = mesh.E()(first, 1);
  while (sharp_at[v].size() == 2 && sharp_at[loop.vertices.front()].size() == 2) {
    if (v == loop.vertices.front()) {
      for (const int e : loop.edges) loop.length += mesh.edge_lengths()[e];
      return loop;
    }
    const int next = sharp_at[v][0] == loop.edges.back() ? sharp_at[v][1] : sharp_at[v][0];
    if (walked[next]) break;
    walked[next] = 1;
    loop.vertices.push_back(v);
    loop.edges.push_back(next);
    v = mesh.E()(next, 0) == v ? mesh.E()(next, 1) : mesh.E()(next, 0);
  }
  return {};
}

/// The face that has loop edge i as (vertex i, vertex i + 1), or −1.
int left_face(const Mesh& mesh, const CreaseLoop& loop, std::size_t i) {
  const int e = loop.edges[i], from = loop.vertices[i];
  const int to = loop.vertices[(i + 1) % loop.vertices.size()];
  for (int j = 0; j < 2; ++j) {
    const int f = mesh.EF()(e, j);
    if (f >= 0 && mesh.F()(f, (mesh.corner_of(f, from) + 1) % 3) == to) return f;
  }
  return -1;
}

/// The angle at loop vertex i of the faces on the left of the loop, turning counter-clockwise from the left face of
/// the outgoing edge to that of the incoming one; NaN if the turn meets the boundary.
double left_angle(const Mesh& mesh, const CreaseLoop& loop, std::size_t i) {
  const std::size_t n = loop.vertices.size();
  const int v = loop.vertices[i], last = left_face(mesh, loop, (i + n - 1) % n);
  double angle = 0;
  for (int f = left_face(mesh, loop, i), steps = 0; f >= 0 && steps <= mesh.valence(v); ++steps) {
    const int corner = mesh.corner_of(f, v);
    angle += mesh.corner_angles()(f, corner);
    if (f == last) return angle;
    f = mesh.neighbor(f, (corner + 1) % 3);  // across the edge from v to its previous corner
  }
  return std::nan("");
}

/// The sum of the corner angles at v, from the mesh's angle defect (2π − Σα inside, π − Σα on the boundary).
double vertex_angle(const Mesh& mesh, int v) {
  return (mesh.is_boundary_vertex(v) ? kPi : 2 * kPi) - mesh.angle_defect()[v];
}

}  // namespace

std::vector<CreaseLoop> closed_crease_loops(const Mesh& mesh, const std::vector<int>& sharp_edges) {
  std::vector<std::vector<int>> sharp_at(static_cast<std::size_t>(mesh.num_vertices()));
  for (const int e : sharp_edges)
    for (int j = 0; j < 2; ++j) sharp_at[mesh.E()(e, j)].push_back(e);
  std::vector<char> walked(static_cast<std::size_t>(mesh.num_edges()), 0);
  std::vector<CreaseLoop> loops;
  for (const int e : sharp_edges) {
    if (walked[e]) continue;
    CreaseLoop loop = trace_loop(mesh, sharp_at, e, walked);
    if (loop.edges.empty()) continue;
    for (std::size_t i = 0; i < loop.vertices.size(); ++i) {
      const double left = left_angle(mesh, loop, i);
      loop.turning_left += kPi - left;
      loop.turning_right += kPi - (vertex_angle(mesh, loop.vertices[i]) - left);
    }
    if (std::isfinite(loop.turning_left)) loops.push_back(std::move(loop));
  }
  return loops;
}

int free_side(const CreaseLoop& loop, double max_length) {
  if (!(loop.length < max_length)) return 0;
  const double left = std::abs(loop.turning_left), right = std::abs(loop.turning_right);
  if (left > kPi && right < kPi / 2) return 1;
  if (right > kPi && left < kPi / 2) return -1;
  return 0;
}

std::vector<unsigned char> freed_loop_sides(const Mesh& mesh, const std::vector<CreaseLoop>& loops, double max_length) {
  std::vector<unsigned char> freed(static_cast<std::size_t>(mesh.num_faces()), 0);
  for (const CreaseLoop& loop : loops) {
    const int side = free_side(loop, max_length);
    if (side == 0) continue;
    for (std::size_t i = 0; i < loop.edges.size(); ++i) {
      const int e = loop.edges[i], left = left_face(mesh, loop, i);
      const int f = side > 0 ? left : (mesh.EF()(e, 0) == left ? mesh.EF()(e, 1) : mesh.EF()(e, 0));
      if (f < 0) continue;
      for (int k = 0; k < 3; ++k)
        if (mesh.FE()(f, k) == e) freed[f] |= static_cast<unsigned char>(1 << k);
    }
  }
  return freed;
}

}  // namespace quadcover
