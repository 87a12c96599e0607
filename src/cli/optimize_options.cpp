#include "cli/optimize_options.h"

#include <limits>
#include <stdexcept>
#include <string>

#include "cli/commands.h"
#include "common/errors.h"
#include "field/feature_alignment.h"
#include "render/html_report.h"
#include "render/plots.h"

namespace quadcover::cli {

namespace {

/// A true/false option (CLI11 also takes 1/0, yes/no) whose help ends with "(true/false)" and shows its default.
void add_switch(CLI::App& cmd, const std::string& name, bool& value, const std::string& help) {
  cmd.add_option(name, value, help + " (true/false)")->capture_default_str();
}

/// The repairs and retries that make the map valid (issue 14): cone merges and moves, fold refinement, retries.
void add_validity_options(CLI::App& cmd, OptimizeCliOptions& options) {
  add_switch(cmd, "--cancel-close-cones", options.cancel_close_cones,
             "Before the map, cancel the branch point pairs of opposite index less than one quad edge apart (they "
             "would land on one lattice point or on neighbouring ones, and the map fold between them); report "
             "field.cancelled_close_pairs");
  add_switch(cmd, "--merge-cones", options.merge_cones,
             "Merge branch point pairs the map puts on one lattice point into one cone and solve the map again when "
             "that leaves fewer flipped or collapsed triangles");
  add_switch(cmd, "--separate-cones", options.separate_cones,
             "When the result is not valid beside branch points that the rounding put on one lattice point within 4 "
             "rings of each other, make the map again with them set apart by re-rounded periods, kept when more "
             "valid; report rounding.coincident_cone_pairs and separated_cones");
  add_switch(cmd, "--move-cones", options.move_cones,
             "Move the branch point of each fake cone pair (the map winds one turn too few or too many around it and "
             "the opposite turn around a vertex within 3 rings) to that vertex and solve the map again, kept while "
             "the map gets more valid; report untangling.moved_wound_cones");
  cmd.add_option("--refine-folds", options.refine_folds,
                 "Rounds of edge splits around the triangles the untangling leaves flipped or collapsed, each "
                 "followed by the untangling on the finer mesh (0 = off); the map then has more triangles (the "
                 "input's vertices first, see the report's refinement and fold_refinement)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd.add_option("--retries", options.validity_retries,
                 "While the result has a flipped or collapsed triangle or a quad mesh whose topology differs from "
                 "the input's, run the job again at up to N nearby densities (+4%, -4%, +8%, ... quads; +2%, -2%, +4%, "
                 "... when --faces/--vertices or --edge-length gave the density) and keep the "
                 "first valid one, else the best (0 = off, and so are the attempts with the curvature field and "
                 "the full optimization when the result is not valid; see the report's validity_retries)")
      ->check(CLI::Range(0, 8))
      ->capture_default_str();
}

}  // namespace

void add_feature_options(CLI::App& cmd, std::string& feature_angle, std::string& features_file, bool& no_features,
                         const std::string& features_help) {
  auto* angle =
      cmd.add_option("--feature-angle", feature_angle,
                     "Sharp features: interior edges whose dihedral angle exceeds DEG degrees (on curves of at least 8 "
                     "such edges, or shorter creases between flat sides and between corners, as a gear's teeth) are "
                     "followed by the field and, with --align, lie on quad edges; 0 or 'off' = no sharp features "
                     "(boundaries are still followed)")
          ->type_name("DEG|off")
          ->capture_default_str();
  auto* features = cmd.add_option("--features", features_file, features_help)->type_name("FILE")->excludes(angle);
  cmd.add_flag("--no-features", no_features,
               "No sharp features (as --feature-angle off); boundaries are still followed")
      ->excludes(angle)
      ->excludes(features);
}

void add_optimize_options(CLI::App& cmd, OptimizeCliOptions& options) {
  cmd.add_option("--field", options.field,
                 "Guiding cross field: curvature = the principal curvature directions on the faces where they are "
                 "reliable (5.1.2), filled in by --fill and smoothed (5.3) with a pull towards them; smooth = the "
                 "smoothest cross field with a weak pull to them (as MIQ), "
                 "lower distortion on organic shapes (Table 7.1 in BENCHMARKS.md); auto = smooth on a closed surface, "
                 "curvature on one with a boundary, and when the smooth field's result is not valid the map is "
                 "made from the curvature field too and the more valid kept (the report's options.field says "
                 "which ran, options.field_auto that it was chosen). Features are followed by all")
      ->check(CLI::IsMember({"auto", "curvature", "smooth"}))
      ->capture_default_str();
  cmd.add_option("--fill", options.fill, kFillHelp)
      ->check(CLI::IsMember({"smooth", "propagate"}))
      ->capture_default_str();
  cmd.add_option("--split-cones", options.split_min_quarters,
                 "Split every interior singularity of the field whose index is at least N/4 in absolute value into "
                 "index ±1/4 ones on nearby vertices (2: half cones too, whose quad vertices have valence 2 or 6; "
                 "3: from three-quarter cones, a valence-1 vertex; 4: whole turns only); report "
                 "field.singularity_moves")
      ->check(CLI::Range(2, 4))
      ->capture_default_str();
  add_feature_options(cmd, options.feature_angle, options.features_file, options.no_features,
                      "Sharp features given instead of detected: " + std::string(kFeatureFileHelp) +
                          "; the field follows them and, with --align, they lie on quad edges, whatever their angle");
  add_switch(cmd, "--align", options.align,
             "Put boundary and sharp feature curves the field follows on integer iso-lines, i.e. on quad edges");
  add_switch(cmd, "--round-curves", options.round_curves,
             "With --align: round the periods and the curves' integers together, so that the cones go where the "
             "curves can be straight (every curve of at least 3 grid units is pinned; quads up to the boundary); "
             "the curves through the map's wrong windings are freed, and when it is still less valid than the map "
             "without, that one is kept (report: aligned_curves[].left_free_because, "
             "rounding.curve_rounding_dropped)");
  cmd.add_option("--square-holes", options.square_hole_units,
                 "Closed sharp-edge loops shorter than N quad edges that turn by a whole turn on one side and run "
                 "straight on the other (the rim of a small hole through a part, a small boss) are followed on the "
                 "straight side only: the quads around them stay an even grid and the hole comes out square, its "
                 "cones on the rim (0 = follow every loop on both sides, the quads shrinking towards small holes)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd.add_option("--optimize", options.optimize,
                 "Distortion optimization of the field's matching (thesis ch. 6) before parameterizing: none; "
                 "relocate = Algorithm 6.1 moving and cancelling branch points, never creating any; full = with "
                 "creation of branch points, then balancing (6.4) when the budget allows. Default relocate: on the "
                 "Table 7.1 bunny (BENCHMARKS.md) it lowers E_D and the branch point count in 0.3 s and keeps the "
                 "quad mesh closed and all-quad with the fewest irregular vertices; full lowers RSD and ARAP "
                 "further but adds branch points, irregular vertices and non-quads and takes 5-50x longer")
      ->check(CLI::IsMember({"none", "relocate", "full"}))
      ->capture_default_str();
  cmd.add_option("--rounding", options.rounding,
                 "Period rounding (6.3) minimizing E_H with the period matrix: direct (nearest lattice point, no "
                 "matrix), greedy (MIQ), search1/2/3 (change up to r periods at a time; the thesis's r = 3), "
                 "exact (closest vector by LLL + enumeration, up to 48 periods, else search3)")
      ->check(CLI::IsMember({"direct", "greedy", "search1", "search2", "search3", "exact"}))
      ->capture_default_str();
  cmd.add_option("--max-iterations", options.max_iterations,
                 "Budget of E_D evaluations for --optimize: -1 = auto (relocate 3000, above 33k faces 1e8 / "
                 "faces and at least 300; full one per 8 interior edges, 3000 to 20000, and at most 2 s + 0.25 ms "
                 "per face, so that the whole pipeline stays "
                 "within the goal times of BENCHMARKS.md), 0 = until converged; "
                 "--time-limit and Ctrl-C also stop it, keeping the best field so far. The report's "
                 "optimize.stopped_by says whether it converged or what stopped it")
      ->check(CLI::Range(-1L, std::numeric_limits<long>::max()))
      ->capture_default_str();
  add_validity_options(cmd, options);
  cmd.add_option("--keep-better", options.keep_better,
                 "Also parameterize the original field and keep whichever map has the lower E_D + E_H (6.1.1); "
                 "reported as optimize.kept. One extra parameterization; false always uses the optimized field")
      ->capture_default_str();
  cmd.add_option("--relaxation", options.relaxation, kRelaxationHelp)
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd.add_option("--max-memory", options.max_memory_gb,
                 "Memory the job may use in GB (0 = what the machine has available); a density whose estimated peak "
                 "is larger is refused before any work, with the largest quad count that fits")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd.add_option("--stiffening", options.stiffening, kStiffeningHelp)
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
}

double parse_feature_angle(const std::string& text) {
  if (text == "off") return 0;
  double degrees = -1;
  std::size_t used = 0;
  try {
    degrees = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !(degrees >= 0 && degrees <= 180))
    throw InputError("--feature-angle", 0, "expected 'off' or an angle in degrees in [0, 180], got '" + text + "'");
  return degrees;
}

Fill parse_fill_option(const std::string& text) {
  try {
    return parse_fill(text);
  } catch (const InputError&) {
    throw InputError("--fill", 0, "expected propagate or smooth, got '" + text + "'");
  }
}

void apply_optimize_options(const OptimizeCliOptions& cli, PipelineOptions& options) {
  auto flag = [](const char* name, auto parse) {
    try {
      return parse();
    } catch (const InputError& e) {
      throw InputError(name, 0, e.what());
    }
  };
  options.param.lattice = parse_lattice(cli.lattice);
  options.param.density.edge_length = cli.edge_length;
  options.param.density.target_quads = cli.quads;
  options.field_style = flag("--field", [&] { return parse_field_style(cli.field); });
  options.fill = parse_fill_option(cli.fill);
  options.split_min_quarters = cli.split_min_quarters;
  options.optimize = flag("--optimize", [&] { return parse_optimize_mode(cli.optimize); });
  options.param.rounding.strategy = flag("--rounding", [&] { return parse_rounding_strategy(cli.rounding); });
  options.max_evaluations = cli.max_iterations;
  options.keep_better = cli.keep_better;
  options.cancel_close_cones = cli.cancel_close_cones;
  options.merge_coincident_cones = cli.merge_cones;
  options.move_wound_cones = cli.move_cones;
  options.separate_coincident_cones = cli.separate_cones;
  options.fold_refinement_rounds = cli.refine_folds;
  options.validity_retries = cli.validity_retries;
  options.param.relaxation.iterations = cli.relaxation;
  options.param.stiffening.max_iterations = cli.stiffening;
  options.max_memory_bytes = static_cast<std::int64_t>(cli.max_memory_gb * 1e9);
  options.param.features.sharp_angle_degrees = cli.no_features ? 0 : parse_feature_angle(cli.feature_angle);
  options.param.alignment.enabled = cli.align;
  options.param.alignment.round_with_periods = cli.round_curves;
  options.square_hole_grid_units = cli.square_hole_units;
}

FeatureFile read_feature_file(const std::string& path) {
  return {path, path.empty() ? std::vector<FeatureEdgeLine>{} : read_feature_edges(path)};
}

std::optional<std::vector<FeatureSegment>> given_features(const FeatureFile& file, const Mesh& mesh,
                                                          const std::vector<int>& mesh_vertex_of_file) {
  if (file.path.empty()) return std::nullopt;
  std::vector<std::pair<int, int>> edges;
  for (const FeatureEdgeLine& l : file.lines) edges.emplace_back(l.a, l.b);
  RefusedFeatureEdge refused;
  std::vector<FeatureSegment> given = feature_segments(mesh, mesh_vertex_of_file, edges, refused);
  using Why = RefusedFeatureEdge::Why;
  if (refused.why == Why::kNone) return given;
  const FeatureEdgeLine& l = file.lines[static_cast<std::size_t>(refused.position)];
  const std::string vertex = "vertex " + std::to_string(refused.vertex + 1);
  throw InputError(
      file.path, l.line,
      refused.why == Why::kNoSuchVertex
          ? vertex + " is not in the mesh (it has " + std::to_string(mesh_vertex_of_file.size()) + " vertices)"
      : refused.why == Why::kVertexInNoFace ? vertex + " is used by no face"
                                            : "vertices " + std::to_string(l.a + 1) + " and " +
                                                  std::to_string(l.b + 1) + " are not joined by an edge of the mesh");
}

void write_optimization_plot(const std::string& path, const nlohmann::json& optimize_report) {
  const nlohmann::json& log = optimize_report.contains("log") ? optimize_report["log"] : nlohmann::json::array();
  if (!log.is_array() || log.empty())
    throw InputError("--plot", 0, "no optimization log to plot (use --optimize relocate or full)");
  write_line_plot(path, optimization_history_plot(log));
}

}  // namespace quadcover::cli
