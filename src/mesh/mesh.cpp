#include "mesh/mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "common/errors.h"
#include "common/union_find.h"
#include "mesh/edge_table.h"

namespace quadcover {

struct MeshBuilder {
  static Mesh make(Eigen::MatrixX3d V, Eigen::MatrixX3i F) {
    Mesh m;
    m.V_ = std::move(V);
    m.F_ = std::move(F);
    m.build_connectivity();
    m.build_geometry();
    return m;
  }
};

namespace {

[[noreturn]] void throw_problems(const PolygonSoup& soup, const ValidationReport& report) {
  std::vector<std::string> lines;
  for (const auto& p : report.problems)
    if (p.fatal) lines.push_back(p.message);
  const std::string file = soup.file.empty() ? std::string("<input>") : soup.file;
  // The count is taken before `lines` is moved into the exception (argument evaluation order is unspecified).
  const std::size_t kinds = lines.size();
  std::string what = file + ": not a valid manifold triangle mesh (" + std::to_string(kinds) + " kind" +
                     (kinds == 1 ? "" : "s") + " of problem)";
  throw TopologyError(std::move(what), std::move(lines));
}

}  // namespace

MeshBuildResult build_mesh(const PolygonSoup& input, const ValidationOptions& options) {
  MeshBuildResult result;
  result.report = validate(input, options);
  if (!result.report.valid()) throw_problems(input, result.report);

  // Source face of every triangle (polygons may have been fanned).
  std::vector<int> source;
  const PolygonSoup triangulated = options.triangulate ? triangulate_polygons(input) : PolygonSoup{};
  const PolygonSoup& soup = options.triangulate ? triangulated : input;
  if (options.triangulate) {
    for (std::size_t f = 0; f < input.num_faces(); ++f)
      for (std::size_t k = 0; k < std::max<std::size_t>(input.face_size(f), 3) - 2; ++k) source.push_back(static_cast<int>(f));
  } else {
    source.resize(soup.num_faces());
    std::iota(source.begin(), source.end(), 0);
  }

  // Drop unreferenced vertices (reported as a warning), keeping the order of the others.
  const auto nv = static_cast<int>(soup.num_vertices());
  result.vertex_map.assign(static_cast<std::size_t>(nv), -1);
  for (std::int64_t v : soup.face_vertices) result.vertex_map[static_cast<std::size_t>(v)] = 0;
  int kept = 0;
  for (int& m : result.vertex_map)
    if (m == 0) m = kept++;
  Eigen::MatrixX3d V(kept, 3);
  for (int v = 0; v < nv; ++v)
    if (result.vertex_map[static_cast<std::size_t>(v)] >= 0) V.row(result.vertex_map[static_cast<std::size_t>(v)]) = soup.positions.row(v);
  const auto nf = static_cast<Eigen::Index>(soup.num_faces());
  Eigen::MatrixX3i F(nf, 3);
  for (Eigen::Index f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) F(f, k) = result.vertex_map[static_cast<std::size_t>(soup.face_begin(static_cast<std::size_t>(f))[k])];

  if (result.report.flipped_faces > 0) {
    std::vector<std::array<std::int64_t, 3>> tris(static_cast<std::size_t>(nf));
    for (Eigen::Index f = 0; f < nf; ++f) tris[static_cast<std::size_t>(f)] = {F(f, 0), F(f, 1), F(f, 2)};
    const EdgeTable edges(static_cast<std::size_t>(kept), tris);
    const OrientationResult orientation = orient_consistently(edges, tris.size(), {});
    for (Eigen::Index f = 0; f < nf; ++f)
      if (orientation.flip[static_cast<std::size_t>(f)]) std::swap(F(f, 1), F(f, 2));
  }
  result.face_source = std::move(source);
  result.mesh = MeshBuilder::make(std::move(V), std::move(F));
  return result;
}

Mesh Mesh::from_triangles(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  const PolygonSoup soup = PolygonSoup::from_triangles(V, F);
  ValidationReport report = validate(soup);
  if (!report.valid()) throw_problems(soup, report);
  if (report.unreferenced_vertices > 0) return build_mesh(soup).mesh;
  return MeshBuilder::make(V, F);
}

int Mesh::valence(int v) const {
  const auto f = fan(v);
  return static_cast<int>(f.size()) + (is_boundary_vertex(v) ? 1 : 0);
}

int Mesh::genus() const {
  int g = 0;
  for (const auto& c : components_) g += c.genus;
  return g;
}

double Mesh::bounding_box_diagonal() const {
  if (V_.rows() == 0) return 0;
  return (V_.colwise().maxCoeff() - V_.colwise().minCoeff()).norm();
}

namespace {

/// Ordered fans (counter-clockwise, a boundary fan from its start). Around vertex v = corner k of face f, the next
/// face counter-clockwise is the one across the face edge opposite corner k+1 (the edge {v, corner k+2}); the
/// previous is across the edge opposite corner k+2. \pre F, FE, EF built.
void ordered_fans(const Mesh& m, std::vector<int>& offsets, std::vector<Mesh::FanCorner>& fan) {
  const int nv = m.num_vertices(), nf = m.num_faces();
  std::vector<int> first_corner(static_cast<std::size_t>(nv), -1);  // some (f,k) at v, preferring a fan start
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = m.F()(f, k);
      const bool starts = m.neighbor(f, (k + 2) % 3) < 0;  // nothing clockwise of this face: a boundary fan start
      if (first_corner[static_cast<std::size_t>(v)] < 0 || starts) first_corner[static_cast<std::size_t>(v)] = 3 * f + k;
    }
  offsets.assign(static_cast<std::size_t>(nv) + 1, 0);
  fan.clear();
  fan.reserve(static_cast<std::size_t>(3 * nf));
  for (int v = 0; v < nv; ++v) {
    offsets[static_cast<std::size_t>(v)] = static_cast<int>(fan.size());
    const int start = first_corner[static_cast<std::size_t>(v)];
    int f = start / 3, k = start % 3;
    do {
      fan.push_back({f, k});
      const int next = m.neighbor(f, (k + 1) % 3);
      if (next < 0) break;
      int nk = 0;
      while (m.F()(next, nk) != v) ++nk;
      f = next;
      k = nk;
    } while (f != start / 3);
  }
  offsets[static_cast<std::size_t>(nv)] = static_cast<int>(fan.size());
}

/// Boundary loops: boundary half-edges a -> b (face to the left) followed from vertex to vertex, each loop from its
/// lowest edge. \pre E, EF built.
void trace_boundary_loops(const Mesh& m, std::vector<std::vector<int>>& loops,
                          std::vector<std::vector<int>>& loop_edges) {
  const int nv = m.num_vertices(), ne = m.num_edges();
  const Eigen::MatrixX2i &E = m.E(), &EF = m.EF();
  std::vector<int> next_boundary_edge(static_cast<std::size_t>(nv), -1);
  for (int e = 0; e < ne; ++e) {
    if (!m.is_boundary_edge(e)) continue;
    const bool positive = EF(e, 0) >= 0;  // the face traverses E0 -> E1
    next_boundary_edge[static_cast<std::size_t>(positive ? E(e, 0) : E(e, 1))] = e;
  }
  loops.clear();
  loop_edges.clear();
  std::vector<char> visited(static_cast<std::size_t>(ne), 0);
  for (int e0 = 0; e0 < ne; ++e0) {
    if (!m.is_boundary_edge(e0) || visited[static_cast<std::size_t>(e0)]) continue;
    std::vector<int> loop, edges;
    int e = e0;
    while (!visited[static_cast<std::size_t>(e)]) {
      visited[static_cast<std::size_t>(e)] = 1;
      const bool positive = EF(e, 0) >= 0;
      const int from = positive ? E(e, 0) : E(e, 1), to = positive ? E(e, 1) : E(e, 0);
      loop.push_back(from);
      edges.push_back(e);
      e = next_boundary_edge[static_cast<std::size_t>(to)];
    }
    loops.push_back(std::move(loop));
    loop_edges.push_back(std::move(edges));
  }
}

/// Component of each face (faces joined through interior edges), numbered in order of their lowest face.
Eigen::VectorXi face_components(const Mesh& m) {
  const int nf = m.num_faces();
  detail::UnionFind faces(nf);
  for (int e = 0; e < m.num_edges(); ++e)
    if (!m.is_boundary_edge(e)) faces.unite(m.EF()(e, 0), m.EF()(e, 1));
  Eigen::VectorXi component(nf);
  std::vector<int> label(static_cast<std::size_t>(nf), -1);
  int nc = 0;
  for (int f = 0; f < nf; ++f) {
    const int r = faces.find(f);
    if (label[static_cast<std::size_t>(r)] < 0) label[static_cast<std::size_t>(r)] = nc++;
    component[f] = label[static_cast<std::size_t>(r)];
  }
  return component;
}

}  // namespace

void Mesh::build_connectivity() {
  const int nv = num_vertices(), nf = num_faces();
  std::vector<std::array<std::int64_t, 3>> tris(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) tris[static_cast<std::size_t>(f)] = {F_(f, 0), F_(f, 1), F_(f, 2)};
  const EdgeTable table(static_cast<std::size_t>(nv), tris);
  const auto ne = static_cast<int>(table.num_edges());

  E_.resize(ne, 2);
  EF_.setConstant(ne, 2, -1);
  EF_corner_.setConstant(ne, 2, -1);
  for (int e = 0; e < ne; ++e) {
    E_(e, 0) = static_cast<int>(table.endpoints(static_cast<std::size_t>(e))[0]);
    E_(e, 1) = static_cast<int>(table.endpoints(static_cast<std::size_t>(e))[1]);
    for (const auto& h : table.incidences(static_cast<std::size_t>(e))) {
      const int side = h.forward ? 0 : 1;
      EF_(e, side) = static_cast<int>(h.tri);
      EF_corner_(e, side) = h.k;
    }
  }
  FE_.resize(nf, 3);
  FE_sign_.resize(nf, 3);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int e = static_cast<int>(table.face_edge(static_cast<std::size_t>(f), k));
      FE_(f, k) = e;
      FE_sign_(f, k) = EF_(e, 0) == f && EF_corner_(e, 0) == k ? 1 : -1;
    }

  boundary_vertex_.assign(static_cast<std::size_t>(nv), 0);
  for (int e = 0; e < ne; ++e)
    if (is_boundary_edge(e)) boundary_vertex_[E_(e, 0)] = boundary_vertex_[E_(e, 1)] = 1;

  ordered_fans(*this, fan_offsets_, fan_);
  trace_boundary_loops(*this, boundary_loops_, boundary_loop_edges_);
  face_component_ = face_components(*this);
  const int nc = nf == 0 ? 0 : face_component_.maxCoeff() + 1;
  components_.assign(static_cast<std::size_t>(nc), ComponentInfo{});
  vertex_component_.resize(nv);
  for (int v = 0; v < nv; ++v) {
    vertex_component_[v] = face_component_[fan(v)[0].face];
    ++components_[static_cast<std::size_t>(vertex_component_[v])].vertices;
  }
  for (int f = 0; f < nf; ++f) ++components_[static_cast<std::size_t>(face_component_[f])].faces;
  for (int e = 0; e < ne; ++e) ++components_[static_cast<std::size_t>(vertex_component_[E_(e, 0)])].edges;
  for (const auto& loop : boundary_loops_) ++components_[static_cast<std::size_t>(vertex_component_[loop[0]])].boundary_loops;
  for (auto& c : components_) {
    c.euler_characteristic = c.vertices - c.edges + c.faces;
    c.genus = (2 - c.euler_characteristic - c.boundary_loops) / 2;
  }
}

void Mesh::build_geometry() {
  const int nv = num_vertices(), nf = num_faces(), ne = num_edges();
  face_area_.resize(nf);
  face_normal_.resize(nf, 3);
  corner_angle_.resize(nf, 3);
  corner_cot_.resize(nf, 3);
  face_b1_.resize(nf, 3);
  face_b2_.resize(nf, 3);
  corner_local_.resize(nf, 3);
  for (int f = 0; f < nf; ++f) {
    const Eigen::Vector3d p[3] = {V_.row(F_(f, 0)), V_.row(F_(f, 1)), V_.row(F_(f, 2))};
    const Eigen::Vector3d cr = (p[1] - p[0]).cross(p[2] - p[0]);
    const double twice_area = cr.norm();
    face_area_[f] = 0.5 * twice_area;
    const Eigen::Vector3d n = cr / twice_area;
    face_normal_.row(f) = n;
    const Eigen::Vector3d b1 = (p[1] - p[0]).normalized();
    const Eigen::Vector3d b2 = n.cross(b1);
    face_b1_.row(f) = b1;
    face_b2_.row(f) = b2;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
      const double cosine = a.dot(b), sine = a.cross(b).norm();
      corner_angle_(f, k) = std::atan2(sine, cosine);
      corner_cot_(f, k) = cosine / sine;
      const Eigen::Vector3d d = p[k] - p[0];
      corner_local_(f, k) = Complex(d.dot(b1), d.dot(b2));
    }
  }
  total_area_ = face_area_.sum();
  edge_length_.resize(ne);
  for (int e = 0; e < ne; ++e) edge_length_[e] = (V_.row(E_(e, 1)) - V_.row(E_(e, 0))).norm();
  mean_edge_length_ = ne > 0 ? edge_length_.mean() : 0.0;

  angle_defect_.resize(nv);
  for (int v = 0; v < nv; ++v) {
    double sum = 0;
    for (const auto& c : fan(v)) sum += corner_angle_(c.face, c.corner);
    angle_defect_[v] = (is_boundary_vertex(v) ? std::numbers::pi : 2 * std::numbers::pi) - sum;
  }

  // ρ_e: the direction of edge e (E0 -> E1) in t's basis divided by its direction in s's basis.
  edge_transport_.setOnes(ne);
  for (int e = 0; e < ne; ++e) {
    if (is_boundary_edge(e)) continue;
    const int s = EF_(e, 0), t = EF_(e, 1);
    const Complex ds = edge_vector_local(s, EF_corner_(e, 0));   // s traverses E0 -> E1
    const Complex dt = -edge_vector_local(t, EF_corner_(e, 1));  // t traverses E1 -> E0
    edge_transport_[e] = (dt / std::abs(dt)) / (ds / std::abs(ds));
  }
}

std::vector<int> Mesh::boundary_edges() const {
  std::vector<int> out;
  for (int e = 0; e < num_edges(); ++e)
    if (is_boundary_edge(e)) out.push_back(e);
  return out;
}

Eigen::MatrixX2i Mesh::edge_endpoints(const std::vector<int>& edges) const {
  Eigen::MatrixX2i out(static_cast<Eigen::Index>(edges.size()), 2);
  for (std::size_t i = 0; i < edges.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = E_.row(edges[i]);
  return out;
}

}  // namespace quadcover
