#include "metrics/report.h"

#include <cstdio>
#include <sstream>

namespace quadcover {

namespace {
template <class M>
nlohmann::json map_json(const M& m) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [k, v] : m) j[std::to_string(k)] = v;
  return j;
}
}  // namespace

// The scalars under their own names; the histograms, the maps and the topology are added by to_json below.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ParamQuality, scale, arap, arap_max, arap_p95, flipped_triangles,
                                   collapsed_triangles, non_positive_triangles, uv_area, energy_curl, energy_harmonic,
                                   branch_points, max_transition_error, max_translation_defect,
                                   max_branch_point_offset)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(QuadQuality, vertices, faces, quads, non_quads, mean_edge_length, rsd_edge_length,
                                   mean_corner_angle, rsd_corner_angle, irregular_vertices, boundary_vertices,
                                   irregular_boundary_vertices)

nlohmann::json to_json(const ParamQuality& q) {
  nlohmann::json j = q;
  j["arap_histogram"] = {{"upper_bounds", q.arap_bins}, {"counts", q.arap_histogram}};
  j["degenerate_triangles"] = q.collapsed_triangles;  // the older name of the collapsed count
  j["branch_points_by_index"] = map_json(q.branch_points_by_index);
  return j;
}

nlohmann::json to_json(const QuadQuality& q) {
  nlohmann::json j = q;
  j["face_sizes"] = map_json(q.face_sizes);
  j["valence_histogram"] = map_json(q.valence_histogram);
  const nlohmann::json topology = to_json(q.topology);  // mesh/surface_counts.h
  for (const char* key : {"manifold", "oriented", "closed", "components", "boundary_loops", "genus",
                          "euler_characteristic", "boundary_edges", "non_manifold_edges", "non_manifold_vertices"})
    j[key] = topology[key];
  return j;
}

nlohmann::json to_json(const SurfaceDistance& d) {
  return {{"bbox_diagonal", d.bbox_diagonal},         {"mean", d.mean},
          {"max", d.max},                             {"mean_to_reference", d.mean_to_reference},
          {"max_to_reference", d.max_to_reference},   {"mean_from_reference", d.mean_from_reference},
          {"max_from_reference", d.max_from_reference}};
}

// Every counter under its own name.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ExtractionReport, quads, non_quads, grid_vertices, boundary_vertices,
                                   unfolded_triangles, moved_vertices, collapsed_edges, flipped_triangles,
                                   degenerate_triangles, torn_seams, non_integer_translations, failed_traces,
                                   dropped_faces, degenerate_faces, boundary_slivers, removed_spikes, removed_doublets,
                                   split_vertices, split_polygons, merged_polygons, boundary_collapsed_triangles,
                                   boundary_added_vertices, boundary_split_polygons, boundary_merged_polygons,
                                   filled_holes, active_parameter_area)

nlohmann::json to_json(const ExtractionReport& r) { return r; }

nlohmann::json to_json(const Report& r) {
  nlohmann::json j;
  j["input"] = r.input;
  j["parameterization"] = r.parameterization ? to_json(*r.parameterization) : nlohmann::json();
  j["extraction"] = r.extraction ? to_json(*r.extraction) : nlohmann::json();
  j["quad_mesh"] = r.quad_mesh ? to_json(*r.quad_mesh) : nlohmann::json();
  j["surface_distance"] = r.surface_distance ? to_json(*r.surface_distance) : nlohmann::json();
  j["seconds"] = r.seconds;
  j["values"] = r.values;
  return j;
}

std::string to_text(const Report& r) {
  std::ostringstream os;
  char buf[256];
  auto line = [&](const char* fmt, auto... v) {
    std::snprintf(buf, sizeof buf, fmt, v...);
    os << "  " << buf << "\n";
  };
  os << r.input << "\n";
  if (r.parameterization) {
    const auto& p = *r.parameterization;
    os << " parameterization\n";
    line("ARAP (normalized, area-weighted): %.5f  (max %.4f, 95%% below %.4f)", p.arap, p.arap_max, p.arap_p95);
    line("flipped triangles: %d, collapsed: %d", p.flipped_triangles, p.collapsed_triangles);
    line("branch points: %d", p.branch_points);
    line("UV area (quad count of a closed map): %.2f", p.uv_area);
    line("max transition error: %.3g, max translation defect: %.3g", p.max_transition_error, p.max_translation_defect);
    line("E_D: %.6g, E_H: %.6g", p.energy_curl, p.energy_harmonic);
  }
  if (r.extraction) {
    const auto& e = *r.extraction;
    os << " extraction\n";
    line("quads: %d, other polygons: %d, boundary vertices: %d", e.quads, e.non_quads, e.boundary_vertices);
    line("untangled: %d triangles (%d vertices moved, %d edges mapped to a point collapsed)", e.unfolded_triangles,
         e.moved_vertices, e.collapsed_edges);
    line("polygons split into quads: %d (%d odd pairs merged first; %d and %d at the boundary), fold holes closed: %d",
         e.split_polygons, e.merged_polygons, e.boundary_split_polygons, e.boundary_merged_polygons, e.filled_holes);
    line("cut out: %d flipped, %d degenerate triangles, %d torn seams, %d failed traces, %d dropped faces",
         e.flipped_triangles, e.degenerate_triangles, e.torn_seams, e.failed_traces, e.dropped_faces);
  }
  if (r.quad_mesh) {
    const auto& q = *r.quad_mesh;
    os << " quad mesh\n";
    line("vertices: %d, faces: %d (quads %d, other %d)", q.vertices, q.faces, q.quads, q.non_quads);
    line("RSD edge length: %.2f %%", q.rsd_edge_length);
    line("RSD corner angle: %.2f %%", q.rsd_corner_angle);
    line("irregular vertices: %d (interior), %d (boundary)", q.irregular_vertices, q.irregular_boundary_vertices);
    line("manifold: %s, closed: %s, Euler characteristic: %d", q.topology.manifold() ? "yes" : "no",
         q.topology.closed() ? "yes" : "no", q.topology.euler_characteristic);
  }
  if (r.surface_distance) {
    const auto& d = *r.surface_distance;
    os << " surface distance (relative to the bounding-box diagonal)\n";
    line("mean: %.3g, max: %.3g", d.mean, d.max);
  }
  return os.str();
}

nlohmann::json rounding_to_json(const ParamOptions& options, const Parameterization& p) {
  const auto& r = p.diagnostics.rounding;
  return {{"strategy", to_string(options.rounding.strategy)},
          {"strategy_used", r.strategy},
          {"E_H", p.energy_harmonic},
          {"h_sym", p.h_sym},
          {"variables", r.variables},
          {"E_H_predicted_direct", r.energy_direct},
          {"E_H_predicted", r.energy_rounded},
          {"candidates", r.candidates},
          {"proven_optimal", r.proven_optimal},
          {"stopped_early", r.stopped_early},
          {"curve_conditions", r.curve_conditions},
          {"curve_conditions_met", r.curve_conditions_met},
          {"curve_lines", r.curve_lines},
          {"curve_rounding_dropped", r.curve_rounding_dropped},
          {"coincident_cone_pairs", r.coincident_cones.size()},
          {"coincident_cone_pairs_left", r.coincident_cone_pairs_left},
          {"separated_cone_pairs", r.separated_cones.size()},
          {"separated_cones", r.separated_cones}};
}

nlohmann::json relaxation_to_json(const Parameterization& p) {
  const auto& r = p.diagnostics.relaxation;
  return {{"iterations", r.iterations},
          {"arap_before", r.rigidity_before},
          {"arap_after", r.rigidity_after},
          {"E_R", r.energy}};
}

nlohmann::json quad_smoothing_to_json(const QuadSmoothingOptions& options, const QuadSmoothingReport& r) {
  return {{"iterations", r.iterations},
          {"rigidity", options.rigidity},
          {"feature_snap", options.feature_snap},
          {"feature_vertices", r.feature_vertices},
          {"edge_length", r.edge_length},
          {"fixed_vertices", r.fixed_vertices},
          {"rejected_moves", r.rejected_moves},
          {"mean_displacement", r.mean_displacement},
          {"max_displacement", r.max_displacement},
          {"slide_boundary", options.slide_boundary},
          {"boundary_vertices", r.boundary_vertices}};
}

// The counters of the untangling and the stiffening under their own names; their prices under the thesis-style
// symbols (E_U, E_K) the reports have always used.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ParamDiagnostics::Untangling, iterations, polish_iterations, regions,
                                   non_positive_before, non_positive_after, stuck_faces, unresolved_faces,
                                   released_vertices, rewound_vertices, cone_disk_vertices, min_det)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ParamDiagnostics::Stiffening, iterations, kept_iteration, flipped_before,
                                   flipped_after)

nlohmann::json untangling_to_json(const Parameterization& p) {
  nlohmann::json j = p.diagnostics.untangling;
  j["E_U"] = p.diagnostics.untangling.energy;
  return j;
}

nlohmann::json stiffening_to_json(const Parameterization& p) {
  nlohmann::json j = p.diagnostics.stiffening;
  j["E_K"] = p.diagnostics.stiffening.energy;
  return j;
}

}  // namespace quadcover
