#include "mesh/validate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <string>

#include "common/union_find.h"
#include "mesh/mesh.h"
#include "mesh/edge_table.h"

namespace quadcover {

const char* to_string(ProblemKind kind) {
  switch (kind) {
    case ProblemKind::Empty: return "empty";
    case ProblemKind::NonFiniteCoordinate: return "non_finite_coordinate";
    case ProblemKind::IndexOutOfRange: return "index_out_of_range";
    case ProblemKind::NotTriangle: return "not_triangle";
    case ProblemKind::RepeatedVertex: return "repeated_vertex";
    case ProblemKind::DegenerateFace: return "degenerate_face";
    case ProblemKind::DuplicateFace: return "duplicate_face";
    case ProblemKind::NonManifoldEdge: return "non_manifold_edge";
    case ProblemKind::NonManifoldVertex: return "non_manifold_vertex";
    case ProblemKind::InconsistentOrientation: return "inconsistent_orientation";
    case ProblemKind::NonOrientable: return "non_orientable";
    case ProblemKind::UnreferencedVertex: return "unreferenced_vertex";
  }
  return "unknown";
}

namespace {

// Numbers in messages are the file's: faces count from 1 (the n-th face of the file), vertex indices are written
// as the file writes them (1-based in OBJ, 0-based in OFF and PLY); the resolved 0-based index follows in
// parentheses where it differs. MeshProblem::faces / vertices stay 0-based.
std::string face_number(long f) { return std::to_string(f + 1); }
std::string vertex_number(const PolygonSoup& soup, std::int64_t v) { return std::to_string(v + soup.index_base); }

// Collects the located elements of one kind of problem into a single message.
struct ProblemCollector {
  const PolygonSoup& soup;
  const ValidationOptions& options;
  ProblemKind kind;
  std::string what, plural;  // e.g. "zero-area face", "zero-area faces"
  std::string hint;          // appended after the listing
  MeshProblem problem{};
  std::string listing;
  std::size_t count = 0;

  ProblemCollector(const PolygonSoup& s, const ValidationOptions& o, ProblemKind k, std::string w, std::string pl)
      : soup(s), options(o), kind(k), what(std::move(w)), plural(std::move(pl)) {
    problem.kind = k;
  }
  void face(long f, const std::string& detail = "") {
    problem.faces.push_back(f);
    add("face " + face_number(f) + " (0-based " + std::to_string(f) + ", " +
        soup.face_location(static_cast<std::size_t>(f)) + ")" + detail);
  }
  void vertex(long v, const std::string& detail = "") {
    problem.vertices.push_back(v);
    const std::string resolved = soup.index_base != 0 ? "0-based " + std::to_string(v) + ", " : std::string();
    add("vertex " + vertex_number(soup, v) + " (" + resolved + soup.vertex_location(static_cast<std::size_t>(v)) + ")" +
        detail);
  }
  void add(const std::string& item) {
    if (count < options.max_listed) listing += (count ? "; " : "") + item;
    ++count;
  }
  void flush(ValidationReport& report, bool fatal = true) {
    if (count == 0) return;
    problem.fatal = fatal;
    problem.message = std::to_string(count) + " " + (count == 1 ? what : plural) + ": " + listing;
    if (count > options.max_listed) problem.message += "; ... and " + std::to_string(count - options.max_listed) + " more";
    problem.message += hint;
    report.problems.push_back(std::move(problem));
  }
};

// Vertices with NaN/inf coordinates.
void check_coordinates(const PolygonSoup& soup, const ValidationOptions& options, ValidationReport& report) {
  const auto nv = static_cast<long>(soup.num_vertices());
  ProblemCollector nonfinite(soup, options, ProblemKind::NonFiniteCoordinate, "vertex with NaN/inf coordinates", "vertices with NaN/inf coordinates");
  for (long v = 0; v < nv; ++v)
    if (!soup.positions.row(v).allFinite()) nonfinite.vertex(v);
  nonfinite.flush(report);
}

// Per-face checks. \return per face: 1 for the triangles whose indices are valid and distinct (`usable`): the
// topological checks below only look at those (the others are already reported).
std::vector<char> check_faces(const PolygonSoup& soup, const ValidationOptions& options, ValidationReport& report) {
  const auto nv = static_cast<long>(soup.num_vertices());
  const auto nf = static_cast<long>(soup.num_faces());
  ProblemCollector range(soup, options, ProblemKind::IndexOutOfRange, "face with a vertex index out of range", "faces with a vertex index out of range");
  ProblemCollector polygon(soup, options, ProblemKind::NotTriangle, "non-triangle face", "non-triangle faces");
  polygon.hint = " (`quadcover repair MESH -o FIXED.obj` splits polygons into triangles)";
  ProblemCollector repeated(soup, options, ProblemKind::RepeatedVertex, "face with a repeated vertex", "faces with a repeated vertex");
  ProblemCollector degenerate(soup, options, ProblemKind::DegenerateFace, "zero-area (degenerate) face", "zero-area (degenerate) faces");
  repeated.hint = " (`quadcover repair MESH -o FIXED.obj` drops them)";
  degenerate.hint = " (`quadcover repair MESH -o FIXED.obj` removes those that carry no surface)";
  std::vector<char> usable(static_cast<std::size_t>(nf), 0);
  for (long f = 0; f < nf; ++f) {
    const std::int64_t* c = soup.face_begin(static_cast<std::size_t>(f));
    const std::size_t n = soup.face_size(static_cast<std::size_t>(f));
    bool ok = true;
    for (std::size_t k = 0; k < n; ++k) {
      if (c[k] < 0 || c[k] >= nv) {
        range.face(f, ": vertex index " + vertex_number(soup, c[k]) + " but the file has " + std::to_string(nv) +
                          " vertices (valid: " + vertex_number(soup, 0) + " to " + vertex_number(soup, nv - 1) + ")");
        ok = false;
        break;
      }
    }
    if (n != 3) {
      polygon.face(f, ": " + std::to_string(n) + " corners");
      continue;
    }
    if (!ok) continue;
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) {
      repeated.face(f);
      continue;
    }
    const Eigen::Vector3d p0 = soup.positions.row(c[0]), p1 = soup.positions.row(c[1]), p2 = soup.positions.row(c[2]);
    if (!p0.allFinite() || !p1.allFinite() || !p2.allFinite()) continue;
    const double twice_area = (p1 - p0).cross(p2 - p0).norm();
    const double longest2 = std::max({(p1 - p0).squaredNorm(), (p2 - p1).squaredNorm(), (p0 - p2).squaredNorm()});
    if (!(twice_area > options.degenerate_tolerance * longest2)) {
      degenerate.face(f);
      usable[static_cast<std::size_t>(f)] = 1;  // still a valid simplex combinatorially: check its topology too
      continue;
    }
    usable[static_cast<std::size_t>(f)] = 1;
  }
  range.flush(report);
  polygon.flush(report);
  repeated.flush(report);
  degenerate.flush(report);
  return usable;
}

// Duplicate faces: equal sorted vertex triples. \return per face: 1 for the repeats.
std::vector<char> check_duplicates(const PolygonSoup& soup, const ValidationOptions& options,
                                   const std::vector<char>& usable, ValidationReport& report) {
  const auto nf = static_cast<long>(soup.num_faces());
  std::vector<std::pair<std::array<std::int64_t, 3>, long>> keys;
  keys.reserve(static_cast<std::size_t>(nf));
  for (long f = 0; f < nf; ++f) {
    if (!usable[static_cast<std::size_t>(f)]) continue;
    const std::int64_t* c = soup.face_begin(static_cast<std::size_t>(f));
    std::array<std::int64_t, 3> k{c[0], c[1], c[2]};
    std::sort(k.begin(), k.end());
    keys.push_back({k, f});
  }
  std::sort(keys.begin(), keys.end());
  ProblemCollector duplicate(soup, options, ProblemKind::DuplicateFace, "duplicate face", "duplicate faces");
  duplicate.hint = " (`quadcover repair MESH -o FIXED.obj` keeps the first of each)";
  std::vector<char> is_duplicate(static_cast<std::size_t>(nf), 0);
  for (std::size_t i = 1; i < keys.size(); ++i) {
    if (keys[i].first == keys[i - 1].first) {
      duplicate.face(keys[i].second, " repeats face " + face_number(keys[i - 1].second));
      is_duplicate[static_cast<std::size_t>(keys[i].second)] = 1;
    }
  }
  duplicate.flush(report);
  return is_duplicate;
}

// Non-manifold edges (in more than two usable triangles). \return per edge of `edges`: 1 for those.
std::vector<char> check_edges(const PolygonSoup& soup, const ValidationOptions& options, const EdgeTable& edges,
                              const std::vector<long>& tri_face, ValidationReport& report) {
  ProblemCollector nm_edge(soup, options, ProblemKind::NonManifoldEdge, "non-manifold edge", "non-manifold edges");
  std::vector<char> bad_edge(edges.num_edges(), 0);
  for (std::size_t e = 0; e < edges.num_edges(); ++e) {
    const auto inc = edges.incidences(e);
    if (inc.size() <= 2) continue;
    bad_edge[e] = 1;
    std::string faces;
    for (const auto& h : inc) faces += (faces.empty() ? "" : ", ") + face_number(tri_face[h.tri]);
    nm_edge.add("edge (" + vertex_number(soup, edges.endpoints(e)[0]) + ", " +
                vertex_number(soup, edges.endpoints(e)[1]) + ") in " + std::to_string(inc.size()) + " faces {" + faces +
                "} (" + soup.face_location(static_cast<std::size_t>(tri_face[inc[0].tri])) + ")");
    for (const auto& h : inc) nm_edge.problem.faces.push_back(tri_face[h.tri]);
  }
  nm_edge.flush(report);
  return bad_edge;
}

// Non-manifold vertices: the faces at v, linked through shared manifold edges at v, must form one fan.
void check_vertex_fans(const PolygonSoup& soup, const ValidationOptions& options, const EdgeTable& edges,
                       const std::vector<std::array<std::int64_t, 3>>& tris, const std::vector<char>& bad_edge,
                       ValidationReport& report) {
  const auto nv = static_cast<long>(soup.num_vertices());
  ProblemCollector nm_vertex(soup, options, ProblemKind::NonManifoldVertex, "non-manifold vertex", "non-manifold vertices");
  {
    // Triangles per vertex in compressed rows (counting sort: one allocation, triangles in increasing order).
    std::vector<std::uint32_t> tri_begin(static_cast<std::size_t>(nv) + 1, 0), tri_of(3 * tris.size());
    for (const auto& t : tris)
      for (int k = 0; k < 3; ++k) ++tri_begin[static_cast<std::size_t>(t[k]) + 1];
    for (std::size_t v = 0; v < static_cast<std::size_t>(nv); ++v) tri_begin[v + 1] += tri_begin[v];
    {
      std::vector<std::uint32_t> fill(tri_begin.begin(), tri_begin.end() - 1);
      for (std::size_t t = 0; t < tris.size(); ++t)
        for (int k = 0; k < 3; ++k) tri_of[fill[static_cast<std::size_t>(tris[t][k])]++] = static_cast<std::uint32_t>(t);
    }
    detail::UnionFind fan(0);
    for (long v = 0; v < nv; ++v) {
      const std::span<const std::uint32_t> vt(tri_of.data() + tri_begin[static_cast<std::size_t>(v)],
                                              tri_of.data() + tri_begin[static_cast<std::size_t>(v) + 1]);
      if (vt.size() <= 1) continue;
      fan.reset(static_cast<int>(vt.size()));
      // Two triangles at v are linked if they share an edge (v, w) that is manifold.
      for (std::size_t i = 0; i < vt.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
          const std::size_t e = edges.face_edge(vt[i], k);
          const auto ep = edges.endpoints(e);
          if (ep[0] != v && ep[1] != v) continue;
          if (bad_edge[e]) continue;
          for (const auto& h : edges.incidences(e)) {
            if (h.tri == vt[i]) continue;
            // vt is sorted (triangles were appended in order): binary search keeps huge valences O(d log d).
            const auto it = std::lower_bound(vt.begin(), vt.end(), h.tri);
            fan.unite(static_cast<int>(i), static_cast<int>(it - vt.begin()));
          }
        }
      }
      int fans = 0;
      for (std::size_t i = 0; i < vt.size(); ++i) fans += fan.find(static_cast<int>(i)) == static_cast<int>(i);
      if (fans > 1) nm_vertex.vertex(v, ": " + std::to_string(fans) + " separate fans of faces meet there");
    }
  }
  nm_vertex.flush(report);
}

// Orientation: along every manifold interior edge the two faces must traverse it in opposite directions.
// Propagate a flip flag per face by BFS; a contradiction means the surface is not orientable.
void check_orientation(const PolygonSoup& soup, const ValidationOptions& options, const EdgeTable& edges,
                       const std::vector<std::array<std::int64_t, 3>>& tris, const std::vector<long>& tri_face,
                       const std::vector<char>& bad_edge, ValidationReport& report) {
  {
    ProblemCollector inconsistent(soup, options, ProblemKind::InconsistentOrientation,
                                  "edge whose two faces disagree in orientation",
                                  "edges whose two faces disagree in orientation");
    for (std::size_t e = 0; e < edges.num_edges(); ++e) {
      const auto inc = edges.incidences(e);
      if (inc.size() != 2 || bad_edge[e]) continue;
      if (inc[0].forward == inc[1].forward) {
        inconsistent.add("edge (" + vertex_number(soup, edges.endpoints(e)[0]) + ", " +
                         vertex_number(soup, edges.endpoints(e)[1]) + ") between faces " +
                         face_number(tri_face[inc[0].tri]) + " and " + face_number(tri_face[inc[1].tri]) + " (" +
                         soup.face_location(static_cast<std::size_t>(tri_face[inc[1].tri])) + ")");
        inconsistent.problem.faces.push_back(tri_face[inc[1].tri]);
      }
    }
    const OrientationResult orientation = orient_consistently(edges, tris.size(), bad_edge);
    const bool orientable = orientation.orientable;
    const long witness = orientable ? -1 : tri_face[orientation.witness];
    const std::size_t flips = orientation.flips;
    if (!orientable) {
      MeshProblem p{ProblemKind::NonOrientable,
                    true,
                    "surface is not orientable (e.g. a Möbius band or Klein bottle): no consistent face orientation "
                    "exists; contradiction found at face " +
                        face_number(witness) + " (0-based " + std::to_string(witness) + ", " +
                        soup.face_location(static_cast<std::size_t>(witness)) + ")",
                    {witness},
                    {}};
      report.problems.push_back(std::move(p));
    } else if (inconsistent.count > 0) {
      if (options.fix_orientation) {
        report.flipped_faces = flips;
      } else {
        inconsistent.hint = " (the surface is orientable: `quadcover repair MESH -o FIXED.obj` reorients it)";
        inconsistent.flush(report);
      }
    }
  }
}

// Unreferenced vertices: a warning; they are dropped when the mesh is built.
void check_unreferenced(const PolygonSoup& soup, const ValidationOptions& options, ValidationReport& report) {
  const auto nv = static_cast<long>(soup.num_vertices());
  {
    std::vector<char> used(static_cast<std::size_t>(nv), 0);
    for (std::size_t i = 0; i < soup.face_vertices.size(); ++i) {
      const std::int64_t v = soup.face_vertices[i];
      if (v >= 0 && v < nv) used[static_cast<std::size_t>(v)] = 1;
    }
    ProblemCollector unref(soup, options, ProblemKind::UnreferencedVertex, "unreferenced vertex (dropped)", "unreferenced vertices (dropped)");
    for (long v = 0; v < nv; ++v)
      if (!used[static_cast<std::size_t>(v)]) unref.vertex(v);
    report.unreferenced_vertices = unref.count;
    unref.flush(report, /*fatal=*/false);
  }
}

}  // namespace

ValidationReport validate(const PolygonSoup& input, const ValidationOptions& options) {
  ValidationReport report;
  const PolygonSoup triangulated = options.triangulate ? triangulate_polygons(input) : PolygonSoup{};
  const PolygonSoup& soup = options.triangulate ? triangulated : input;
  const auto nv = static_cast<long>(soup.num_vertices());
  const auto nf = static_cast<long>(soup.num_faces());
  if (nv == 0 || nf == 0) {
    report.problems.push_back({ProblemKind::Empty, true,
                               (soup.file.empty() ? std::string("<input>") : soup.file) + ": mesh is empty (" +
                                   std::to_string(nv) + " vertices, " + std::to_string(nf) + " faces)",
                               {}, {}});
    return report;
  }

  check_coordinates(soup, options, report);
  const std::vector<char> usable = check_faces(soup, options, report);
  const std::vector<char> is_duplicate = check_duplicates(soup, options, usable, report);

  // Edge incidences of the usable triangles.
  std::vector<std::array<std::int64_t, 3>> tris;
  std::vector<long> tri_face;
  for (long f = 0; f < nf; ++f) {
    if (!usable[static_cast<std::size_t>(f)] || is_duplicate[static_cast<std::size_t>(f)]) continue;
    const std::int64_t* c = soup.face_begin(static_cast<std::size_t>(f));
    tris.push_back({c[0], c[1], c[2]});
    tri_face.push_back(f);
  }
  const EdgeTable edges(static_cast<std::size_t>(nv), tris);
  const std::vector<char> bad_edge = check_edges(soup, options, edges, tri_face, report);
  check_vertex_fans(soup, options, edges, tris, bad_edge, report);
  check_orientation(soup, options, edges, tris, tri_face, bad_edge, report);
  check_unreferenced(soup, options, report);
  return report;
}

}  // namespace quadcover