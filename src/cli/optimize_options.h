#pragma once
// Command-line options of the low-distortion optimization (thesis Chapter 6) for commands that parameterize
// (param, remesh): --optimize none|relocate|full, --rounding direct|greedy|search1|search2|search3|exact,
// --max-iterations N, --field, --keep-better, --relaxation, --stiffening, turned into PipelineOptions. The global
// --time-limit and Ctrl-C stop the optimization early with the best state so far (Algorithm 6.1 only ever accepts
// E_D decreases, so the state at any moment is the best one): the job then parameterizes that state.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "field/feature_alignment.h"
#include "io/feature_edge_file.h"
#include "mesh/mesh.h"
#include "optimize/optimize_field.h"
#include "param/relaxation.h"
#include "param/stiffening.h"
#include "pipeline/pipeline_options.h"

namespace quadcover::cli {

struct OptimizeCliOptions {
  std::string lattice = "rotated";  ///< see param/lattice.h
  double edge_length = 0;           ///< density: quad edge length h (0: from `quads` or the default)
  /// Density: target quad count (remesh --faces/--vertices: a closed quad mesh has about as many vertices as faces,
  /// V - F = χ + F - E with E = 2F).
  int quads = 0;
  std::string optimize = "relocate";  ///< see optimize/optimize_field.h
  std::string rounding = "search3";   ///< see param/period_rounding.h
  long max_iterations = kAutoBudget;  ///< E_D evaluations of Algorithm 6.1 (0 = unlimited, -1 = auto)
  bool keep_better = true;            ///< see parameterize_best()
  bool cancel_close_cones = true;     ///< PipelineOptions::cancel_close_cones
  bool merge_cones = true;            ///< PipelineOptions::merge_coincident_cones
  bool move_cones = true;             ///< PipelineOptions::move_wound_cones
  bool separate_cones = true;         ///< PipelineOptions::separate_coincident_cones
  int refine_folds = 6;               ///< PipelineOptions::fold_refinement_rounds
  int validity_retries = PipelineOptions{}.validity_retries;  ///< PipelineOptions::validity_retries
  std::string field = "auto";         ///< field stage preset (field/compute_frame_field.h, FieldStyle)
  std::string fill = "smooth";        ///< FieldOptions::fill: smooth or propagate (thesis 5.1.2)
  int split_min_quarters = PipelineOptions{}.split_min_quarters;  ///< PipelineOptions::split_min_quarters
  int relaxation = RelaxationOptions{}.iterations;      ///< see param/relaxation.h
  int stiffening = StiffeningOptions{}.max_iterations;  ///< see param/stiffening.h
  double max_memory_gb = 0;  ///< see PipelineOptions::max_memory_bytes (0 = the machine's available memory)
  std::string feature_angle = "35";  ///< sharp feature angle in degrees, or "off" (= 0), field/feature_alignment.h
  std::string features_file;         ///< --features FILE: the sharp edges given (io/feature_edge_file.h)
  bool no_features = false;          ///< --no-features: no sharp features (= --feature-angle off)
  bool align = true;                 ///< see ParamOptions::alignment
  bool round_curves = ParamOptions{}.alignment.round_with_periods;  ///< ParamOptions::alignment.round_with_periods
  double square_hole_units = PipelineOptions{}.square_hole_grid_units;  ///< PipelineOptions::square_hole_grid_units
};

/// --fill as FieldOptions::fill. \throw InputError naming --fill for another word.
Fill parse_fill_option(const std::string& text);

/// Adds --field, --fill, --feature-angle, --align, --optimize, --rounding, --max-iterations, --keep-better,
/// --relaxation, --stiffening and --max-memory to `cmd` (validated by CLI11, --feature-angle by
/// apply_optimize_options).
/// \pre options outlives cmd.
void add_optimize_options(CLI::App& cmd, OptimizeCliOptions& options);

/// Sets the lattice, density, field, feature, optimization, rounding, relaxation and stiffening options of the
/// pipeline from the command line. \throw InputError (naming the flag) for an unknown field style, fill, mode or
/// rounding strategy, or a feature angle that is neither 'off' nor a number of degrees in [0, 180].
void apply_optimize_options(const OptimizeCliOptions& cli, PipelineOptions& options);

/// The feature file's format, for help texts.
inline constexpr const char* kFeatureFileHelp =
    "a text file with one edge per line, two vertex numbers counted from 1 in the mesh file's order ('#' comments)";

/// --feature-angle DEG|off (default as given), --features FILE (help text `features_help`) and --no-features, one of
/// them at most (CLI11 refuses two with exit 2). \pre the strings and the flag outlive cmd.
void add_feature_options(CLI::App& cmd, std::string& feature_angle, std::string& features_file, bool& no_features,
                         const std::string& features_help);

/// "off" -> 0, else the number of degrees in [0, 180]. \throw InputError naming --feature-angle otherwise.
double parse_feature_angle(const std::string& text);

/// A --features file, read before the mesh so that a malformed one fails before any work.
struct FeatureFile {
  std::string path;  ///< empty: no --features
  std::vector<FeatureEdgeLine> lines;
};
/// Nothing for an empty path. \throw InputError as read_feature_edges (io/feature_edge_file.h).
FeatureFile read_feature_file(const std::string& path);

/// The file's edges on the loaded mesh, as FeatureOptions::given (nothing without a file). `mesh_vertex_of_file`
/// maps the mesh file's vertices to the mesh's (-1: used by no face). \throw InputError (the feature file and its
/// line) for a vertex the mesh file does not have or uses in no face, or two vertices not joined by an edge of the
/// mesh.
std::optional<std::vector<FeatureSegment>> given_features(const FeatureFile& file, const Mesh& mesh,
                                                          const std::vector<int>& mesh_vertex_of_file);

/// Thesis Figure 6.1 from an "optimize" report object: E_D and the branch point count over the E_D evaluations
/// of Algorithm 6.1. Written as SVG for a ".svg" path, else PNG (atomically). \throw InputError if the log is
/// empty (--optimize none).
void write_optimization_plot(const std::string& path, const nlohmann::json& optimize_report);

}  // namespace quadcover::cli
