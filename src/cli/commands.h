#pragma once
// Each subcommand registers itself on the CLI11 app; main() only dispatches and maps errors to exit codes.
// The shared machinery every command uses (global options, progress, Ctrl-C, batch, atomic outputs) is in
// cli/common.h, which has a short guide at its top.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

namespace quadcover::cli {

/// Options every subcommand shares (added to a subcommand by add_global_options() in cli/common.h).
struct GlobalOptions {
  bool json = false;      ///< --json: machine-readable result on stdout
  bool quiet = false;     ///< -q: nothing but errors
  bool verbose = false;   ///< -v: every progress report as its own line, extra detail
  double time_limit = 0;  ///< --time-limit SECONDS: ask long stages to stop after this long (0 = none)
  int jobs = 0;           ///< -j: files processed at once in batch mode (0 = all cores)
  bool overwrite_input = false;  ///< --overwrite-input: an output may replace an input file
  bool skip_existing = false;    ///< --skip-existing: an input any of whose outputs exists is skipped
  std::string format;            ///< --format: mesh format written to "-" (standard output); "" = OBJ
  /// The subcommand being run (set when CLI11 meets it): run_batch checks its output options before any work.
  const CLI::App* command = nullptr;
};

/// --stiffening N of the commands that parameterize (param, remesh): see param/stiffening.h.
inline constexpr const char* kStiffeningHelp =
    "Local stiffening against folds (beyond the thesis, as in MIQ): while triangles are flipped, re-solve the final "
    "harmonic correction at most N times with weights raised on distorted triangles, keeping the map with the "
    "fewest flips. Periods, branch points, seams and aligned curves are unchanged; the price E_K is reported "
    "(E_D + E_H + E_R + E_K = 1/2 |X - grad phi|^2). 0 = off";

/// --relaxation N of the commands that parameterize (param, remesh): see param/relaxation.h.
inline constexpr const char* kRelaxationHelp =
    "ARAP relaxation of the final map (beyond the thesis): at most N local/global rounds in which the map follows "
    "the rotations nearest to its own Jacobians (with 10% of the field kept in the target) instead of the field. "
    "Periods, branch points, seams and aligned curves are unchanged; each round reuses the factored system and "
    "lowers the energy. The price E_R and the ARAP distortion before and after are reported "
    "(E_D + E_H + E_R + E_K = 1/2 |X - grad phi|^2). 0 = off";

/// --fill of the commands that compute a field (field, param, remesh): see FieldOptions::fill.
inline constexpr const char* kFillHelp =
    "Frames of the faces whose curvature frames are not trusted: smooth (global power-field solve, few branch "
    "points) or propagate (the thesis's trusted propagation, 5.1.2: breadth-first parallel transport from the "
    "trusted faces); the smoothing (5.3) runs after either";

/// Exit codes: 0 success, 1 internal/numerical failure, 2 bad input or usage, 3 partial result written (a Ctrl-C
/// or --time-limit skipped or cut short an improving stage: the outputs are complete and checked, not fully improved).
enum ExitCode { kOk = 0, kInternal = 1, kBadInput = 2, kPartial = 3 };

/// The exit code of a job's result: kPartial if its summary says "partial", else kOk. \pre none
inline int result_exit_code(const nlohmann::json& result) {
  return result.is_object() && result.value("partial", false) ? kPartial : kOk;
}

}  // namespace quadcover::cli
