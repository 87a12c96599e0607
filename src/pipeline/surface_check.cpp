#include "pipeline/surface_check.h"

#include <utility>

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

nlohmann::json to_json(const SurfaceCheck& s) {
  return {{"input", to_json(s.input)},
          {"output", to_json(s.output)},
          {"same_topology", s.same_topology},
          {"closed_all_quads", s.closed_all_quads},
          {"problems", s.problems}};
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

}  // namespace

std::vector<std::string> remesh_warnings(const SurfaceCheck& check, const ExtractionReport& extraction) {
  std::vector<std::string> warnings;
  for (const std::string& p : check.problems) warnings.push_back("remesh changed the surface: " + p);
  for (std::string& w : extraction_repairs(extraction)) warnings.push_back(std::move(w));
  if (check.input.boundary_loops > 0 && check.output.non_quads > 0)  // a closed input's are a problem above
    warnings.push_back(std::to_string(check.output.non_quads) + " of the " + std::to_string(check.output.faces) +
                       " faces are not quads");
  return warnings;
}

}  // namespace quadcover
