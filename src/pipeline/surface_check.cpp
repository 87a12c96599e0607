#include "pipeline/surface_check.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>

#include "common/union_find.h"

namespace quadcover {

SurfaceCheck check_surface(const Mesh& input, int num_vertices, const std::vector<std::vector<int>>& faces) {
  SurfaceCheck s;
  s.input = surface_counts(input);
  s.output = surface_counts(num_vertices, faces);
  const SurfaceCounts &a = s.input, &b = s.output;
  auto differ = [&](const char* what, int x, int y) {
    if (x != y)
      s.problems.push_back(std::string(what) + ": " + std::to_string(y) + " in the quad mesh, " + std::to_string(x) +
                           " in the input");
  };
  differ("components", a.components, b.components);
  differ("boundary loops", a.boundary_loops, b.boundary_loops);
  differ("Euler characteristic", a.euler_characteristic, b.euler_characteristic);
  if (!b.manifold())
    s.problems.push_back("the quad mesh is not manifold (" + std::to_string(b.non_manifold_edges) + " edges, " +
                         std::to_string(b.non_manifold_vertices) + " vertices, " + std::to_string(b.degenerate_faces) +
                         " degenerate faces)");
  if (!b.oriented())
    s.problems.push_back("the quad mesh is not consistently oriented (" + std::to_string(b.inconsistent_edges) +
                         " edges whose two faces disagree)");
  s.same_topology = s.problems.empty();
  const bool closed = a.boundary_loops == 0;
  s.closed_all_quads = !closed || (b.boundary_loops == 0 && b.non_quads == 0 && s.same_topology);
  if (closed && b.non_quads > 0)
    s.problems.push_back("the input is closed but " + std::to_string(b.non_quads) + " faces are not quads");
  return s;
}

namespace {

Eigen::Vector3d centroid(const Eigen::MatrixX3d& V, const std::vector<int>& vertices) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int v : vertices) c += V.row(v).transpose();
  return c / static_cast<double>(std::max<std::size_t>(1, vertices.size()));
}

/// The boundary loops of a polygon mesh as places: boundary edges (used once) grouped by shared vertices.
std::vector<SurfacePlace> boundary_loop_places(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces) {
  const auto uses = polygon_edge_uses(faces);
  detail::UnionFind sets(static_cast<int>(V.rows()));
  for (const auto& [e, n] : uses)
    if (n == 1) sets.unite(e.first, e.second);
  std::map<int, std::pair<int, std::vector<int>>> loops;  // root -> (edges, vertices)
  for (const auto& [e, n] : uses) {
    if (n != 1) continue;
    auto& [edges, vertices] = loops[sets.find(e.first)];
    ++edges;
    vertices.push_back(e.first);
    vertices.push_back(e.second);
  }
  std::vector<SurfacePlace> places;
  for (auto& [root, loop] : loops) {
    std::vector<int>& vertices = loop.second;
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    places.push_back({"boundary loop", -1, loop.first, centroid(V, vertices)});
  }
  return places;
}

}  // namespace

void locate_surface_problems(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces,
                             SurfaceCheck& check) {
  check.places.clear();
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (faces[f].size() != 4)
      check.places.push_back(
          {"non-quad face", static_cast<int>(f) + 1, static_cast<int>(faces[f].size()), centroid(V, faces[f])});
  if (check.output.boundary_loops > check.input.boundary_loops)
    for (SurfacePlace& p : boundary_loop_places(V, faces)) check.places.push_back(std::move(p));
}

nlohmann::json to_json(const SurfaceCheck& s) {
  nlohmann::json places = nlohmann::json::array();
  for (const SurfacePlace& p : s.places)
    places.push_back({{"kind", p.kind}, {"face", p.face}, {"size", p.size}, {"at", {p.at.x(), p.at.y(), p.at.z()}}});
  return {{"input", to_json(s.input)},
          {"output", to_json(s.output)},
          {"same_topology", s.same_topology},
          {"closed_all_quads", s.closed_all_quads},
          {"problems", s.problems},
          {"places", places}};
}

namespace {

/// One sentence listing the repairs of the extraction, or none.
std::vector<std::string> extraction_repairs(const ExtractionReport& r) {
  struct Repair {
    int ExtractionReport::*count;
    const char *one, *many;
  };
  static constexpr Repair kRepairs[] = {
      {&ExtractionReport::unfolded_triangles, "folded triangle unfolded", "folded triangles unfolded"},
      {&ExtractionReport::moved_vertices, "vertex moved by the fold repair", "vertices moved by the fold repair"},
      {&ExtractionReport::collapsed_edges, "edge mapped to a point collapsed", "edges mapped to a point collapsed"},
      {&ExtractionReport::flipped_triangles, "flipped triangle cut out", "flipped triangles cut out"},
      {&ExtractionReport::degenerate_triangles, "collapsed triangle cut out", "collapsed triangles cut out"},
      {&ExtractionReport::torn_seams, "torn seam treated as boundary", "torn seams treated as boundary"},
      {&ExtractionReport::non_integer_translations, "non-integer transition", "non-integer transitions"},
      {&ExtractionReport::failed_traces, "iso-line that could not be followed", "iso-lines that could not be followed"},
      {&ExtractionReport::dropped_faces, "face dropped", "faces dropped"},
      {&ExtractionReport::degenerate_faces, "degenerate face dropped", "degenerate faces dropped"},
      {&ExtractionReport::removed_spikes, "spike removed", "spikes removed"},
      {&ExtractionReport::split_vertices, "pinched vertex split", "pinched vertices split"},
      {&ExtractionReport::filled_holes, "hole filled", "holes filled"}};
  std::vector<std::string> repairs;
  for (const Repair& k : kRepairs)
    if (const int n = r.*k.count; n > 0) repairs.push_back(std::to_string(n) + " " + (n == 1 ? k.one : k.many));
  if (repairs.empty()) return {};
  std::string line = "the extraction repaired the map (";
  for (std::size_t i = 0; i < repairs.size(); ++i) line += (i ? ", " : "") + repairs[i];
  return {line + "): the quad mesh is not the exact integer grid of the map there"};
}

/// "where: non-quad face 12 (5 sides) at (x, y, z); ...": the first few places, the rest counted.
std::string places_sentence(const std::vector<SurfacePlace>& places) {
  constexpr std::size_t kShown = 5;
  std::string line = "where: ";
  char at[96];
  for (std::size_t i = 0; i < std::min(kShown, places.size()); ++i) {
    const SurfacePlace& p = places[i];
    std::snprintf(at, sizeof at, " at (%.6g, %.6g, %.6g)", p.at.x(), p.at.y(), p.at.z());
    if (i) line += "; ";
    line += p.kind;
    if (p.face > 0) line.append(" ").append(std::to_string(p.face));
    line.append(" (").append(std::to_string(p.size)).append(p.face > 0 ? " sides)" : " edges)").append(at);
  }
  if (places.size() > kShown)
    line += "; and " + std::to_string(places.size() - kShown) + " more in the report's surface_check.places";
  return line;
}

}  // namespace

std::vector<std::string> remesh_warnings(const SurfaceCheck& check, const ExtractionReport& extraction) {
  std::vector<std::string> warnings;
  for (const std::string& p : check.problems) warnings.push_back("remesh changed the surface: " + p);
  if (!check.problems.empty() && !check.places.empty()) warnings.push_back(places_sentence(check.places));
  for (std::string& w : extraction_repairs(extraction)) warnings.push_back(std::move(w));
  if (const int n = extraction.boundary_slivers; n > 0)
    warnings.push_back(std::to_string(n) + (n == 1 ? " sliver" : " slivers") +
                       " between the boundary and an iso-line it crosses twice cut off: the quad mesh's boundary "
                       "follows the iso-line there (the report's extraction.boundary_slivers)");
  if (check.input.boundary_loops > 0 && check.output.non_quads > 0)  // a closed input's are a problem above
    warnings.push_back(std::to_string(check.output.non_quads) + " of the " + std::to_string(check.output.faces) +
                       " faces are not quads");
  return warnings;
}

}  // namespace quadcover
