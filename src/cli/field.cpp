// `quadcover field MESH... -o FIELD.json`: the guiding frame field of thesis Chapter 5 (principal curvature
// frames, trusted regions, propagation, smoothing) with its matching and branch points.
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/optimize_options.h"
#include "cli/registry.h"
#include "common/errors.h"
#include "field/compute_frame_field.h"
#include "field/feature_alignment.h"
#include "field/indices.h"
#include "io/feature_edge_file.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"

namespace quadcover::cli {

namespace {

struct FieldCmdOptions : MeshFiles {
  std::string method = "hp";
  double csm_radius = CurvatureOptions{}.csm_radius;
  double trusted = FieldOptions{}.trusted_fraction;
  double lambda = FieldOptions{}.lambda;
  int rounds = FieldOptions{}.smoothing_rounds;
  std::string feature_angle = "35";
  std::string features;  ///< a feature file, or the old spelling DEG | off (see legacy_features)
  bool no_features = false;
  std::string save_features;  ///< --save-features FILE: the sharp edges the field followed, in the --features format
  std::string fill = "smooth";
  double fill_alignment = FieldOptions{}.fill_alignment;
  double fill_unit_weight = FieldOptions{}.fill_unit_weight;
  int fill_iterations = FieldOptions{}.fill_iterations;
};

/// The field command's old `--features DEG|off` (before --feature-angle and feature files): 'off' -> 0 (no sharp
/// feature and no boundary alignment), an angle in (0, 180) -> itself; nothing for anything else (a feature file).
std::optional<double> legacy_features(const std::string& text) {
  if (text == "off") return 0.0;
  std::size_t used = 0;
  double degrees = -1;
  try {
    degrees = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != text.size()) return std::nullopt;
  if (!(degrees > 0 && degrees < 180))
    throw InputError("--features", 0,
                     "expected a feature file, or 'off' or an angle in degrees in (0, 180), got '" + text + "'");
  return degrees;
}

FieldOptions to_field_options(const FieldCmdOptions& opt) {
  FieldOptions o;
  if (opt.method == "hp")
    o.curvature.method = CurvatureMethod::HildebrandtPolthier;
  else if (opt.method == "csm")
    o.curvature.method = CurvatureMethod::CohenSteinerMorvan;
  else
    throw InputError("--method", 0, "expected hp or csm, got '" + opt.method + "'");
  o.curvature.csm_radius = opt.csm_radius;
  o.trusted_fraction = opt.trusted;
  o.lambda = opt.lambda;
  o.smoothing_rounds = opt.rounds;
  o.fill = parse_fill_option(opt.fill);
  o.fill_alignment = opt.fill_alignment;
  o.fill_unit_weight = opt.fill_unit_weight;
  o.fill_iterations = opt.fill_iterations;
  o.features.sharp_angle_degrees = opt.no_features ? 0 : parse_feature_angle(opt.feature_angle);
  if (const std::optional<double> legacy = legacy_features(opt.features)) {
    o.features.boundaries = *legacy > 0;  // 'off' aligned to nothing, not even the boundaries
    o.features.sharp_angle_degrees = *legacy;
  }
  return o;
}

nlohmann::json complex_array(const Eigen::VectorXcd& z) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < z.size(); ++i) a.push_back({z[i].real(), z[i].imag()});
  return a;
}
nlohmann::json rows_array(const Eigen::MatrixX3d& M) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < M.rows(); ++i) a.push_back({M(i, 0), M(i, 1), M(i, 2)});
  return a;
}
template <class V>
nlohmann::json vector_array(const V& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}

// The document written to FIELD.json: everything needed to draw the field or to reuse it with the same mesh.
nlohmann::json field_document(const std::string& input, const Mesh& mesh, const FrameFieldResult& r,
                              const FieldOptions& o) {
  nlohmann::json j;
  j["format"] = "quadcover-frame-field";
  j["version"] = 1;
  j["mesh"] = input;
  j["vertices"] = mesh.num_vertices();
  j["edges"] = mesh.num_edges();
  j["faces"] = mesh.num_faces();
  j["conventions"] =
      "X, Y: complex [re, im] per face in the face basis b1 = unit(p1 - p0), b2 = n x b1; Y = iX. matching: per edge "
      "(edge_vertices order, from face EF0 to EF1), counter-clockwise quarter turns, X_t ~ i^m rho_e X_s. "
      "cross_u, cross_v: unit 3D cross directions per face. quarter_index = 4 * index.";
  j["options"] = {
      {"method", o.curvature.method == CurvatureMethod::HildebrandtPolthier ? "hp" : "csm"},
      {"csm_radius", o.curvature.csm_radius},
      {"trusted_fraction", o.trusted_fraction},
      {"lambda", o.lambda},
      {"smoothing_rounds", o.smoothing_rounds},
      {"fill", to_string(o.fill)},
      {"fill_alignment", o.fill_alignment},
      {"fill_unit_weight", o.fill_unit_weight},
      {"fill_iterations", o.fill_iterations},
      {"boundary_alignment", o.features.boundaries},
      {"sharp_angle_degrees", o.features.given ? nlohmann::json() : nlohmann::json(o.features.sharp_angle_degrees)},
      {"given_feature_edges", o.features.given ? nlohmann::json(o.features.given->size()) : nlohmann::json()}};
  j["X"] = complex_array(r.field.X);
  j["Y"] = complex_array(r.field.Y);
  const CrossDirections cross = cross_directions(mesh, r.field);
  j["cross_u"] = rows_array(cross.u);
  j["cross_v"] = rows_array(cross.v);
  nlohmann::json edges = nlohmann::json::array();
  for (int e = 0; e < mesh.num_edges(); ++e) edges.push_back({mesh.E()(e, 0), mesh.E()(e, 1)});
  j["edge_vertices"] = std::move(edges);
  j["matching"] = vector_array(r.field.matching);
  j["kappa_max"] = vector_array(r.curvature.kappa_max);
  j["kappa_min"] = vector_array(r.curvature.kappa_min);
  j["stability"] = vector_array(r.stability);
  nlohmann::json trusted = nlohmann::json::array(), constrained = nlohmann::json::array();
  for (int t = 0; t < mesh.num_faces(); ++t) {
    if (r.trusted[static_cast<std::size_t>(t)]) trusted.push_back(t);
    if (r.constrained[static_cast<std::size_t>(t)]) constrained.push_back(t);
  }
  j["trusted_faces"] = std::move(trusted);
  j["constrained_faces"] = std::move(constrained);
  nlohmann::json bps = nlohmann::json::array();
  for (const auto& b : r.branch_points)
    bps.push_back({{"vertex", b.vertex},
                   {"quarter_index", b.quarter_index},
                   {"index", b.quarter_index / 4.0},
                   {"position", {mesh.V()(b.vertex, 0), mesh.V()(b.vertex, 1), mesh.V()(b.vertex, 2)}}});
  j["branch_points"] = std::move(bps);
  j["energy_smooth"] = r.energy_smooth;
  j["energy_smooth_initial"] = r.energy_smooth_initial;
  j["energy_align"] = r.energy_align;
  return j;
}

/// --save-features: the sharp edges `features` select on `mesh` (those the field followed), in the mesh file's numbers
/// (file_vertex: mesh vertex -> its number in the file).
void save_followed_features(const std::string& path, const Mesh& mesh, const std::vector<int>& file_vertex,
                            const FeatureOptions& features) {
  std::vector<std::pair<int, int>> edges;
  for (const int e : feature_constraints(mesh, features).feature_edges)
    edges.emplace_back(file_vertex[static_cast<std::size_t>(mesh.E()(e, 0))],
                       file_vertex[static_cast<std::size_t>(mesh.E()(e, 1))]);
  std::ostringstream source;
  if (features.given)
    source << "given by --features";
  else
    source << "dihedral angle above " << features.sharp_angle_degrees << " degrees, on curves of at least "
           << features.min_curve_edges << " such edges or crisp between corners";
  write_feature_edges(
      path, edges,
      {"quadcover: the " + std::to_string(edges.size()) + " sharp edges the field followed (" + source.str() + ")",
       "one edge per line, two vertex numbers counted from 1 (the --features format)"});
}

nlohmann::json run_field(const std::string& input, const std::string& output, const FieldCmdOptions& opt,
                         ProgressSink& progress) {
  FieldOptions options = to_field_options(opt);
  // A feature file unless the old spelling; a malformed one fails before any work.
  const FeatureFile feature_file = read_feature_file(legacy_features(opt.features) ? "" : opt.features);
  FileVertices file_vertices;  // load_mesh warns about dropped unreferenced vertices (issue 18 item 16)
  const Mesh mesh = load_mesh(input, progress, file_vertices, /*written_back=*/false);
  if (const auto given = given_features(feature_file, mesh, file_vertices.mesh_of)) options.features.given = given;
  const FrameFieldResult r = compute_frame_field_detailed(mesh, options, progress);
  write_json_atomically(output, field_document(input, mesh, r, options));
  if (!opt.save_features.empty())
    save_followed_features(opt.save_features, mesh, file_vertices.of_mesh, options.features);

  const Eigen::VectorXi q = cross_field_quarter_index(mesh, r.field);
  std::map<int, int> by_index;  // quarter index -> count
  for (const auto& b : r.branch_points) ++by_index[b.quarter_index];
  nlohmann::json counts = nlohmann::json::object();
  for (const auto& [quarter, n] : by_index) counts[std::to_string(quarter) + "/4"] = n;
  int constrained = 0, trusted = 0;
  for (int t = 0; t < mesh.num_faces(); ++t) {
    constrained += r.constrained[static_cast<std::size_t>(t)];
    trusted += r.trusted[static_cast<std::size_t>(t)];
  }
  return {{"file", input},
          {"output", output},
          {"faces", mesh.num_faces()},
          {"branch_points", r.branch_points.size()},
          {"branch_points_by_index", counts},
          {"index_sum", q.sum() / 4.0},
          {"euler_characteristic", mesh.euler_characteristic()},
          {"boundary_loops", mesh.num_boundary_loops()},
          {"energy_smooth", r.energy_smooth},
          {"energy_smooth_initial", r.energy_smooth_initial},
          {"trusted_faces", trusted},
          {"constrained_faces", constrained}};
}

void register_field(CLI::App* cmd, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<FieldCmdOptions>();
  add_mesh_inputs(*cmd, *opt,
                  "Output FIELD.json (one input) or folder (several inputs); default: next to the input as "
                  "NAME.field.json");
  cmd->add_option("--method", opt->method,
                  "Principal curvature estimator: hp (Hildebrandt-Polthier) or csm "
                  "(Cohen-Steiner-Morvan, robust on noisy meshes)")
      ->capture_default_str();
  cmd->add_option("--csm-radius", opt->csm_radius, "CSM disk radius in mean edge lengths")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--trusted", opt->trusted, "Fraction of most stable curvature frames to keep (5.1.2)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--lambda", opt->lambda, "Smoothing weight lambda of (5.3), in (0, 1]")
      ->check(CLI::Validator(
          [](std::string& s) {
            try {
              const double v = std::stod(s);
              if (v > 0 && v <= 1) return std::string();
            } catch (const std::exception&) {
            }
            return "expected a number in (0, 1], got " + s;
          },
          "in (0, 1]"))
      ->capture_default_str();
  cmd->add_option("--rounds", opt->rounds, "Smoothing rounds (re-matching between rounds); 0 disables smoothing")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  add_feature_options(*cmd, opt->feature_angle, opt->features, opt->no_features,
                      "Sharp features given instead of detected: " + std::string(kFeatureFileHelp) +
                          "; the field follows them whatever their angle. The old forms DEG (= --feature-angle DEG) "
                          "and 'off' (no sharp feature and no boundary alignment either) are still read");
  cmd->add_option("--save-features", opt->save_features,
                  "Also write the sharp edges the field followed (detected or given) to FILE in the --features "
                  "format, to edit and give back with --features (one input)")
      ->type_name("FILE");
  cmd->add_option("--fill", opt->fill, kFillHelp)->capture_default_str();
  cmd->add_option("--fill-alignment", opt->fill_alignment,
                  "Smooth fill: strength mu of the alignment to the trusted curvature frames")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--fill-unit-weight", opt->fill_unit_weight,
                  "Smooth fill: Ginzburg-Landau weight sigma of the unit-length penalty (0: linear solve only)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--fill-iterations", opt->fill_iterations,
                  "Smooth fill: majorize-minimize steps for the unit-length penalty")
      ->check(CLI::Range(0, 10000))
      ->capture_default_str();
  add_global_options(*cmd, global);
  run_on_inputs(*cmd, global, exit_code, opt->inputs,
                {"faces", "branch_points", "index_sum", "euler_characteristic", "energy_smooth"},
                [opt](const std::string& input, bool batch, ProgressSink& progress) {
                  if (batch && !opt->save_features.empty())
                    throw InputError("--save-features", 0,
                                     "takes one input: a batch would write every mesh's edges "
                                     "to one file");
                  return run_field(input, output_path(input, opt->output, batch, ".field.json"), *opt, progress);
                });
}

const CommandRegistrar registrar{30, "field", register_field,
                                 "Compute the guiding cross field (principal curvature, trusted regions, smoothing; "
                                 "thesis ch. 5), its matching and branch points, and write them as JSON"};

}  // namespace

}  // namespace quadcover::cli
