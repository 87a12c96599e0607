#include "pipeline/job_report.h"

#include <algorithm>
#include <cmath>

#include "common/quarter_turn.h"
#include "field/feature_alignment.h"
#include "metrics/feature_fidelity.h"
#include "metrics/param_quality.h"
#include "metrics/quad_quality.h"
#include "metrics/report.h"
#include "metrics/surface_distance.h"
#include "param/seams.h"

namespace quadcover {

// (Outside the anonymous namespace: nlohmann finds it by argument-dependent lookup.)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FoldRefinementReport, rounds, kept_rounds, split_edges, added_faces,
                                   non_positive_before, non_positive_after, untangle_iterations, seconds)

namespace {

nlohmann::json mesh_json(const Mesh& mesh) {
  return {{"vertices", mesh.num_vertices()},
          {"faces", mesh.num_faces()},
          {"genus", mesh.genus()},
          {"boundary_loops", mesh.num_boundary_loops()},
          {"components", mesh.num_components()}};
}

nlohmann::json options_json(const PipelineOptions& o) {
  return {{"field", to_string(o.field_style)},
          {"split_min_quarters", o.split_min_quarters},
          {"optimize", to_string(o.optimize)},
          {"max_iterations", o.max_evaluations},
          {"keep_better", o.keep_better},
          {"lattice", to_string(o.param.lattice)},
          {"rounding", to_string(o.param.rounding.strategy)},
          {"relaxation", o.param.relaxation.iterations},
          {"stiffening", o.param.stiffening.max_iterations},
          {"align_curves", o.param.alignment.enabled},
          {"round_curves", o.param.alignment.round_with_periods},
          {"square_holes", o.square_hole_grid_units},
          {"freed_hole_rims", o.param.density.hole_rims.size()},
          {"smooth_quads", o.smoothing.iterations},
          {"smooth_rigidity", o.smoothing.rigidity},
          {"refine_curve_triangles", o.refine_curve_triangles},
          {"boundary_quads", o.extraction.quadrangulate_boundary},
          {"merge_coincident_cones", o.merge_coincident_cones},
          {"move_wound_cones", o.move_wound_cones},
          {"fold_refinement_rounds", o.fold_refinement_rounds},
          {"validity_retries", o.validity_retries},
          {"feature_angle",
           o.param.features.given ? nlohmann::json() : nlohmann::json(o.param.features.sharp_angle_degrees)},
          {"given_feature_edges",
           o.param.features.given ? nlohmann::json(o.param.features.given->size()) : nlohmann::json()},
          {"fill", to_string(o.fill)}};
}

/// The curves the field stage followed (field/feature_alignment.h with the job's feature options): the faces whose
/// cross was fixed to a boundary or sharp edge, and the sharp edges.
nlohmann::json features_json(const Mesh& mesh, const PipelineOptions& o) {
  const FeatureConstraints c = feature_constraints(mesh, field_stage_options(o).features);
  const bool given = o.param.features.given.has_value();
  return {{"sharp_angle_degrees", given ? nlohmann::json() : nlohmann::json(o.param.features.sharp_angle_degrees)},
          {"given_edges", given ? nlohmann::json(o.param.features.given->size()) : nlohmann::json()},
          {"boundaries", o.param.features.boundaries},
          {"crisp_crease_degrees", o.param.features.crisp_crease_degrees},
          {"sharp_edges", c.feature_edges.size()},
          {"constrained_faces", std::count(c.constrained.begin(), c.constrained.end(), 1)}};
}

/// The branch points of the field the map was made from (the map's own cones are parameterization.branch_points).
nlohmann::json field_json(const ParamJob& job) {
  nlohmann::json list = nlohmann::json::array();
  int odd = 0, even = 0;
  for (const BranchPoint& b : job.map.branch_points) {
    (mod4(b.quarter_index) == 2 ? even : odd) += 1;
    list.push_back({{"vertex", b.vertex}, {"quarter_index", b.quarter_index}, {"index", b.quarter_index / 4.0}});
  }
  const bool original = job.options.optimize == OptimizeMode::None;  // the map's field was the field stage's
  return {{"branch_points_initial", job.field_branch_points},
          {"singularity_moves", job.field_singularity_moves},
          {"cancelled_close_pairs",
           {{"original", original ? job.cancelled_close_pairs : 0},
            {"optimized", original ? 0 : job.cancelled_close_pairs}}},
          {"branch_points", list},
          {"b_odd", odd},
          {"b_even", even},
          {"unfixed_even_branch_points", job.map.diagnostics.unfixed_even_branch_points}};
}

nlohmann::json curves_json(const Parameterization& map) {
  nlohmann::json curves = nlohmann::json::array();
  double worst = 0;
  for (const auto& c : map.aligned_curves) {
    curves.push_back({{"edges", c.edges.size()},
                      {"coordinate", c.coordinate == 0 ? "u" : "v"},
                      {"value", c.value},
                      {"max_deviation", c.max_deviation},
                      {"enforced", c.enforced},
                      {"left_free_because", c.enforced ? nlohmann::json() : nlohmann::json(c.left_free_because)}});
    worst = std::max(worst, c.max_deviation);
  }
  return {{"curves", curves}, {"max_deviation", worst}, {"conflicts", map.diagnostics.alignment_conflicts}};
}

/// The map's validity and distortion, measured on `uv` (the written coordinates) with the job's transitions.
nlohmann::json map_json(const Mesh& mesh, const Parameterization& map, const Eigen::MatrixX3cd& uv) {
  Parameterization written = map;
  written.uv = uv;
  nlohmann::json j = to_json(param_quality(mesh, written));
  const SeamReport seams = measure_seams(mesh, uv, 1e-9);
  const FlipReport flips = flipped_triangles(mesh, uv);
  j["seamless"] = seams.seamless;
  j["parameter_extent"] = seams.parameter_extent;
  j["cut_edges"] = seams.cut_edges;
  j["parameter_area"] = flips.parameter_area;
  j["flipped_faces"] = flips.flipped_faces;
  // Interior vertices the written map winds around other than the field's index says (0-based, as flipped_faces).
  const std::vector<int> wrong = wrong_winding_vertices(mesh, written);
  j["wrong_windings"] = wrong.size();
  j["wrong_winding_vertices"] = wrong;
  return j;
}

/// What the curve, cone and fold refinements added (pipeline/curve_refinement.h, cone_refinement.h,
/// fold_refinement.h): the map lives on input + these.
nlohmann::json refinement_json(const Mesh& input, const ParamJob& job) {
  const CurveRefinement& r = job.refinement;
  nlohmann::json split = nlohmann::json::array();
  for (const auto& [a, b] : r.split) split.push_back({a, b});
  return {{"split_edges", r.split.size()}, {"cone_split_edges", job.cone_splits},  {"added_vertices", r.split.size()},
          {"added_faces", r.added_faces},  {"faces", job.mesh(input).num_faces()}, {"split", split}};
}

/// What the fold refinement did (pipeline/fold_refinement.h), its price E_F under that name.
nlohmann::json fold_refinement_json(const FoldRefinementReport& f) {
  nlohmann::json j = f;
  j["E_F"] = f.energy;
  return j;
}

/// The validity retries (pipeline/validity_retries.h): every attempt's density and validity, and the one kept.
nlohmann::json validity_retries_json(const ParamJob& job) {
  nlohmann::json attempts = nlohmann::json::array();
  for (const ValidityAttempt& a : job.validity_attempts)
    attempts.push_back({{"quads_factor", a.quads_factor},
                        {"field", to_string(a.field_style)},
                        {"optimize", to_string(a.optimize)},
                        {"crisp_creases", a.crisp_creases},
                        {"edge_length", a.edge_length},
                        {"valid", a.validity.valid()},
                        {"topology_changes", a.validity.topology_changes},
                        {"non_positive_triangles", a.validity.non_positive},
                        {"wrong_windings", a.validity.wrong_windings},
                        {"non_quads", a.validity.non_quads},
                        {"seconds", a.seconds}});
  return {{"attempts", attempts}, {"used", job.validity_attempt_used}};
}

nlohmann::json seconds_json(const StageSeconds& seconds) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [stage, s] : seconds) j[stage] = s;
  return j;
}

nlohmann::json stage_memory_json(const std::string& stage, std::int64_t peak_bytes, int input_faces) {
  return {{"stage", stage},
          {"peak_bytes", peak_bytes},
          {"bytes_per_face", input_faces > 0 ? std::llround(static_cast<double>(peak_bytes) / input_faces) : 0}};
}

/// The "memory" section: the process peak so far and each stage's peak, also per input face.
nlohmann::json memory_json(const StagePeakBytes& peaks, int input_faces) {
  nlohmann::json stages = nlohmann::json::array();
  for (const auto& [stage, bytes] : peaks) stages.push_back(stage_memory_json(stage, bytes, input_faces));
  return {{"peak_bytes", process_peak_resident_bytes()},
          {"input_faces", input_faces},
          {"huge_pages", malloc_asks_for_huge_pages()},
          {"stages", stages}};
}

}  // namespace

nlohmann::json param_report(const Mesh& input_mesh, const ParamJob& job, const Eigen::MatrixX3cd& uv,
                            const std::string& input) {
  const Parameterization& map = job.map;
  const Mesh& mesh = job.mesh(input_mesh);
  nlohmann::json r;
  r["schema_version"] = kReportSchemaVersion;
  r["job"] = "param";
  r["input"] = input;
  r["mesh"] = mesh_json(input_mesh);
  r["refinement"] = refinement_json(input_mesh, job);
  r["fold_refinement"] = fold_refinement_json(job.fold_refinement);
  r["validity_retries"] = validity_retries_json(job);
  r["options"] = options_json(job.options);
  r["options"]["field_auto"] = job.field_style_auto;
  r["edge_length"] = map.edge_length;
  r["density"] = {{"target_quads", job.density.target_quads},
                  {"first_quads", job.density.first_quads},
                  {"quads", job.density.quads},
                  {"resolves", job.density.resolves},
                  {"raised_for_loop", job.density.raised.rim ? 0 : job.density.raised.loop},
                  {"raised_for_hole_rim", job.density.raised.rim ? job.density.raised.loop : 0},
                  {"raised_quads_factor", job.density.raised.quads_factor},
                  {"component_density", map.component_density}};
  r["field"] = field_json(job);
  // The input's sharp edges and the faces they constrain: a refinement's split halves are not new features.
  r["field"]["features"] = features_json(input_mesh, job.options);
  r["parameterization"] = map_json(mesh, map, uv);
  r["parameterization"]["h_sym"] = map.h_sym;
  r["optimize"] = job.optimize;
  r["rounding"] = rounding_to_json(job.options.param, map);
  r["relaxation"] = relaxation_to_json(map);
  r["stiffening"] = stiffening_to_json(map);
  r["untangling"] = untangling_to_json(map);
  r["untangling"]["merged_cone_pairs"] = job.merged_cone_pairs;
  r["untangling"]["cone_merge_rounds"] = job.merge_rounds;
  r["untangling"]["moved_wound_cones"] = job.moved_wound_cones;
  r["untangling"]["wound_cone_rounds"] = job.wound_cone_rounds;
  const ParamJob::ConeSeparation& separation = job.cone_separation;
  nlohmann::json& separated = r["untangling"]["cone_separation"];
  separated = {{"tried", separation.tried}, {"kept", separation.kept}};
  if (separation.tried) {  // the counts of the map it made
    separated["non_positive_triangles"] = separation.validity.non_positive;
    separated["wrong_windings"] = separation.validity.wrong_windings;
  }
  r["aligned_curves"] = curves_json(map);
  r["extraction"] = nullptr;
  r["quad_mesh"] = nullptr;
  r["surface_distance"] = nullptr;
  r["feature_fidelity"] = nullptr;
  r["quad_smoothing"] = nullptr;
  r["surface_check"] = nullptr;
  r["boundary_loops"] = nullptr;
  r["warnings"] = job.warnings;
  r["cut_short"] = job.cut_short;
  r["seconds"] = seconds_json(job.seconds);
  r["memory"] = memory_json(job.peak_bytes, input_mesh.num_faces());
  return r;
}

void add_report_stage(nlohmann::json& report, const std::string& stage, const StageCost& cost) {
  report["seconds"][stage] = cost.seconds;
  nlohmann::json& memory = report["memory"];
  memory["stages"].push_back(stage_memory_json(stage, cost.peak_bytes, memory["input_faces"].get<int>()));
  memory["peak_bytes"] = process_peak_resident_bytes();
}

nlohmann::json remesh_report(const Mesh& mesh, const RemeshJob& job, const std::string& input) {
  StageMeter meter;
  nlohmann::json r = param_report(mesh, job.param, job.param.map.uv, input);
  r["job"] = "remesh";
  const QuadMesh& q = job.extraction.mesh;
  r["extraction"] = to_json(job.extraction.report);
  r["quad_mesh"] = to_json(quad_quality(q));
  r["surface_distance"] = to_json(surface_distance(q.V, q.faces, mesh.V(), mesh.F()));
  FeatureFidelityOptions fidelity;
  fidelity.followed = job.param.options.param.features;  // the curves this job's field followed
  r["feature_fidelity"] = feature_fidelity_to_json(feature_fidelity(mesh, q.V, q.faces, fidelity));
  r["quad_smoothing"] = quad_smoothing_to_json(job.param.options.smoothing, job.smoothing);
  r["surface_check"] = to_json(job.surface);
  r["boundary_loops"] = to_json(job.boundary_loops);
  add_report_stage(r, "metrics", meter.lap());
  return r;
}

nlohmann::json report_summary(const nlohmann::json& r) {
  const nlohmann::json& p = r["parameterization"];
  nlohmann::json optimize = r["optimize"];
  optimize.erase("log");  // in the --report file; the summary stays short
  nlohmann::json s = {{"edge_length", r["edge_length"]},
                      {"branch_points", p["branch_points"]},
                      {"h_sym", p["h_sym"]},
                      {"flipped_triangles", p["flipped_triangles"]},
                      {"non_positive_triangles", p["non_positive_triangles"]},
                      {"seamless", p["seamless"]},
                      {"E_D", p["energy_curl"]},
                      {"E_H", p["energy_harmonic"]},
                      {"arap", p["arap"]},
                      {"optimize", optimize},
                      {"rounding", r["rounding"]},
                      {"partial", !r["cut_short"].empty()}};
  if (r["quad_mesh"].is_null()) {  // param: the numbers of the input mesh
    for (const char* key : {"vertices", "faces", "genus", "boundary_loops"}) s[key] = r["mesh"][key];
    return s;
  }
  const nlohmann::json& q = r["quad_mesh"];
  const nlohmann::json& e = r["extraction"];
  for (const char* key : {"vertices", "faces", "quads", "non_quads", "rsd_edge_length", "rsd_corner_angle",
                          "irregular_vertices", "manifold", "closed"})
    s[key] = q[key];
  s["input_faces"] = r["mesh"]["faces"];
  s["same_topology"] = r["surface_check"]["same_topology"];
  s["features_covered_percent"] = r["feature_fidelity"]["total"]["covered_percent"];
  s["distance_max"] = r["surface_distance"]["max"];
  s["repairs"] = e["failed_traces"].get<int>() + e["dropped_faces"].get<int>() + e["torn_seams"].get<int>();
  return s;
}

}  // namespace quadcover
