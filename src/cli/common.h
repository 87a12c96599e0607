#pragma once
// Shared machinery of the quadcover commands: global options, progress on stderr, Ctrl-C / --time-limit,
// batch processing and atomic outputs.
//
// ---- Guide for command authors (src/cli/<name>.cpp) -------------------------------------------------------------
//
//   namespace {
//   struct XOptions : MeshFiles { double knob = 1; };
//
//   void register_x(CLI::App& app, GlobalOptions& global, int& exit_code) {
//     auto opt = std::make_shared<XOptions>();
//     CLI::App* cmd = app.add_subcommand("x", "One line saying what x does");
//     add_mesh_inputs(*cmd, *opt, "Output file (one input) or folder (several inputs)");  // MESH... -o OUT
//     add_global_options(*cmd, global);   // --json -q -v --time-limit -j --overwrite-input --skip-existing --format
//     cmd->callback([opt, &global, &exit_code] {
//       BatchSpec spec;
//       spec.inputs = opt->inputs;
//       spec.summary_columns = {"faces", "E_D"};            // keys of the returned JSON shown in the summary table
//       exit_code = run_batch(spec, global, [&](const std::string& input, ProgressSink& progress) {
//         const Mesh mesh = load_mesh(input, progress);             // throws InputError/TopologyError; warns
//         Result r = compute(mesh, options, progress);              // long stages honour progress.cancelled()
//         write_file_atomically(output_for(input, opt->output, spec, ".x.obj"), ...);  // never a partial file
//         return nlohmann::json{{"faces", ...}, {"E_D", ...}};      // printed with --json or tabulated
//       });
//     });
//   }
//   const CommandRegistrar registrar{30, "x", register_x};
//   }  // namespace
//
// - One input: the job runs on the calling thread with a live progress bar (a TTY) or plain lines (not a TTY);
//   its exceptions propagate to main(), which prints them and maps them to the exit code (0 ok, 1 internal,
//   2 bad input). The returned JSON is printed (--json) or shown as "key: value" lines unless --quiet.
// - Several inputs or a folder: files run in parallel (-j, default all cores); a failing file prints its error,
//   the others continue; a summary table (or a JSON document with --json) follows; the exit code is the worst.
// - Ctrl-C or --time-limit make progress.cancelled() return true: the stage stops and returns its best result so
//   far, and the command still writes it. A second Ctrl-C, SIGTERM, SIGHUP, SIGQUIT or SIGPIPE remove every
//   temporary file and exit with 128 + the signal at once; a crash signal removes them too before it kills.
// - Outputs (the options named in kOutputOptions: a file with one input, a folder with several) are checked before
//   any work: folders are created, an unwritable place fails at once, an output that is an input file (also
//   through a link) is refused unless --overwrite-input (checked again at every write), and with --skip-existing
//   an input whose output exists is skipped. "-" as the one input reads standard input, "-" as output writes
//   standard output (the result lines then go to stderr) in the mesh format --format names.
// - A line "warning: ..." reported to the progress sink (see warn()) is always shown on stderr unless --quiet.
// ------------------------------------------------------------------------------------------------------------------
#include <chrono>
#include <functional>
#include <iosfwd>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cli/commands.h"
#include "common/progress.h"
#include "mesh/degenerate_faces.h"
#include "mesh/mesh.h"

namespace quadcover::cli {

// ---- options ------------------------------------------------------------------------------------------------

/// Adds --json, -q/--quiet, -v/--verbose, --time-limit SECONDS and -j/--jobs N to a subcommand.
/// \pre global outlives cmd.
void add_global_options(CLI::App& cmd, GlobalOptions& global);

/// Adds the positional "mesh" argument: one or more existing files or folders, or "-" (standard input).
/// \pre inputs outlives cmd.
void add_input_option(CLI::App& cmd, std::vector<std::string>& inputs,
                      const std::string& description = "Input mesh files (.obj .off .ply .stl) or folders of them");

/// The files of a command that reads meshes and writes one output per mesh.
struct MeshFiles {
  std::vector<std::string> inputs;  ///< files and/or folders, as given
  std::string output;               ///< a file for one input, a folder for several; empty: next to the input
};

/// Adds the positional mesh inputs (add_input_option) and -o/--output, described by `output_help`, bound to
/// `files`. \pre files outlives cmd.
void add_mesh_inputs(CLI::App& cmd, MeshFiles& files, const std::string& output_help,
                     const std::string& input_help = "Input mesh files (.obj .off .ply .stl) or folders of them");

// ---- cancellation -------------------------------------------------------------------------------------------

/// Installs the signal handlers: the first Ctrl-C sets the interrupt flag; a second one, SIGTERM, SIGHUP, SIGQUIT
/// and SIGPIPE remove the temporary files of unfinished writes and exit with 128 + signal; SIGSEGV, SIGBUS,
/// SIGFPE, SIGILL and SIGABRT remove them and then take their default action (not under a sanitizer). \pre none
void install_interrupt_handler();
/// Runs `job` on a new thread while the calling thread takes the asynchronous signals (SIGINT, SIGTERM, SIGHUP,
/// SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGXCPU) with sigwait and acts on them as the handlers of
/// install_interrupt_handler() do. They stay blocked in every thread the job starts, so a library that swaps in its
/// own handler for a while (METIS traps SIGTERM while it orders) never receives them. The caller is the main
/// thread, which the kernel prefers for a signal sent to the process; a thread that existed before (OpenBLAS starts
/// one) still has the handlers. Returns job's value. \pre called on the main thread before any thread of ours
/// exists, after install_interrupt_handler(); job does not throw.
int run_watching_signals(const std::function<int()>& job);
/// True after Ctrl-C (or request_interrupt()). \pre none
bool interrupted();
/// Sets / clears the interrupt flag (tests; also the SIGINT handler's action). \pre none
void request_interrupt();
void clear_interrupt();  ///< \pre none
/// The time the run started (first call; main() calls it at start-up). --time-limit counts from here. \pre none
std::chrono::steady_clock::time_point run_start_time();

// ---- progress -----------------------------------------------------------------------------------------------

/// How a TerminalProgress writes.
struct ProgressStyle {
  bool live = false;      ///< redraw one line with a bar (\r) instead of printing plain lines
  bool quiet = false;     ///< print nothing but "warning: ..." reports (cancellation still works)
  bool verbose = false;   ///< plain mode: print every report
  std::string prefix;     ///< put in front of every line (batch mode: the file name)
  double delay = 1.0;     ///< seconds before anything is shown: quick commands stay silent
  double interval = 1.0;  ///< plain mode: at most one line per interval (live mode redraws every 0.1 s)
  int width = 100;        ///< live mode: columns of the terminal
};

/// The style for stderr: live bar when stderr is a terminal, plain lines otherwise, per the global options. \pre none
ProgressStyle stderr_progress_style(const GlobalOptions& global);

/// A ProgressSink for the command line: stage name, bar or percentage, the stage's message (iteration, E_D, ...)
/// and an ETA from the stage's elapsed time and fraction. cancelled() is true after Ctrl-C or past the deadline.
/// Thread-safe: several sinks may share one stream (batch mode).
class TerminalProgress final : public ProgressSink {
 public:
  using Clock = std::chrono::steady_clock;
  /// deadline: Clock::time_point::max() for none. \pre out outlives the sink.
  TerminalProgress(std::ostream& out, ProgressStyle style, Clock::time_point deadline = Clock::time_point::max());
  /// stderr, stderr_progress_style(global), deadline from --time-limit counted from run_start_time(). \pre none
  explicit TerminalProgress(const GlobalOptions& global);
  ~TerminalProgress() override;

  void report(std::string_view stage, double fraction, std::string_view message) override;
  bool cancelled() const override;
  double seconds_left() const override;
  /// Ends the live line (called by the destructor). \pre none
  void finish();

  /// One line of progress as shown: "stage  45%  message  ETA 3s" (plain) or with a bar (live). Exposed for tests.
  /// \pre width >= 1 when bar.
  static std::string format_line(std::string_view stage, double fraction, std::string_view message, double eta_seconds,
                                 bool bar, int width);

 private:
  std::ostream& out_;
  ProgressStyle style_;
  Clock::time_point deadline_, start_, stage_start_, last_print_;
  std::string stage_;
  bool printed_any_ = false, live_dirty_ = false;
  mutable bool announced_stop_ = false;
  mutable std::mutex mutex_;
};

/// The mutex every writer to stderr from worker threads takes (progress lines, per-file results). \pre none
std::mutex& stderr_mutex();

/// Reports "warning: <text>" to `progress`: TerminalProgress shows it on its own line at once (batch mode too),
/// unless --quiet. \pre none
void warn(ProgressSink& progress, const std::string& text);

/// `soup` repaired as `quadcover repair` does, built: the zero-area triangles that carry no surface removed
/// (mesh/degenerate_faces.h, what was removed in `removed`), faces turned to a consistent orientation, polygons left
/// fanned into triangles. \throw InputError, TopologyError as build_mesh (what cannot be repaired).
MeshBuildResult build_repaired(PolygonSoup soup, DegenerateFaceRemoval& removed);

/// Reads and validates a mesh (read_mesh + build_mesh) and warns through `progress` about what the input loses on
/// the way: unreferenced vertices are dropped, so the vertex numbers of outputs are no longer the input's.
/// \throw InputError, TopologyError as read_mesh / build_mesh.
Mesh load_mesh(const std::string& input, ProgressSink& progress);

/// The file's own vertices, for outputs over the input mesh that keep the file's vertex numbers (`param`) and for
/// inputs that name them (feature files).
struct FileVertices {
  Eigen::MatrixX3d positions;  ///< every vertex of the file, unreferenced ones included (when written back)
  std::vector<int> of_mesh;    ///< mesh vertex -> its 0-based number in the file
  std::vector<int> mesh_of;    ///< file vertex -> mesh vertex, -1 for one used by no face
};
/// load_mesh that also returns the file's vertices; with `written_back` (the outputs keep the file's unreferenced
/// vertices) the warning says that they are kept, else that they are dropped. With `new_surface` (the output is a new
/// mesh of the surface: `remesh`) polygons are fan-triangulated from their first corner instead of refused, and
/// vertices at one position are merged (a surface cut at its texture seams) unless that leaves no manifold; warnings
/// say how many. \throw InputError, TopologyError as read_mesh / build_mesh.
Mesh load_mesh(const std::string& input, ProgressSink& progress, FileVertices& file_vertices, bool written_back,
               bool new_surface = false);

// ---- batch --------------------------------------------------------------------------------------------------

/// Files named on the command line, with every folder replaced by its mesh files (.obj .off .ply .stl, not
/// recursive, sorted by name); a file named twice (same normalized path) is kept once, at its first place.
/// \throw InputError for a path that does not exist or a folder without meshes.
std::vector<std::string> expand_inputs(const std::vector<std::string>& args);

/// True if the arguments ask for batch mode: more than one argument or a folder. \pre none
bool is_batch(const std::vector<std::string>& args);

/// The output names (without suffix) of a batch's files, in order, distinct among files writing to one folder
/// (output_dir, or each input's own folder when output_dir is empty). The rule (also in every command's --help):
///  1. a file's name is its stem: "a/bunny.obj" -> "bunny";
///  2. files sharing folder and stem whose parent folders' names differ get "<parent>_" in front: "a_bunny";
///  3. ... whose extensions differ get "_<ext>" appended: "bunny_obj", "bunny_off" (both 2 and 3 may apply);
///  4. a name still taken (by another input's own name or an earlier renamed file) gets "_2", "_3", ... in input
///     order. Unrenamed files keep their plain names.
/// Deterministic: depends only on the list and output_dir, not on the scheduling. \pre none
std::vector<std::string> batch_output_stems(const std::vector<std::string>& files, const std::string& output_dir);

/// Where a batch writes the output of `input`: output_dir / (name + suffix), e.g. ("a/bunny.obj", "out",
/// ".quad.obj") -> "out/bunny.quad.obj". With an empty output_dir: next to the input. The name is the input's
/// stem, or, while process_files runs a batch holding `input`, its batch_output_stems entry (two inputs of one
/// batch never write the same file). While run_batch runs, a path that is an input file throws InputError (unless
/// --overwrite-input) and, with --skip-existing, an existing one throws SkippedExisting: call it before the work.
/// \throw InputError, SkippedExisting as said above.
std::string batch_output_path(const std::string& input, const std::string& output_dir, const std::string& suffix);

/// The naming rule of batch_output_stems in one sentence, and what happens to existing files, for --help.
extern const char* const kBatchNamingHelp;

/// Thrown by batch_output_path (and the output checks of run_batch) under --skip-existing when an output of the
/// input exists: the input is skipped, which is not a failure.
class SkippedExisting : public std::runtime_error {
 public:
  /// \pre none
  explicit SkippedExisting(const std::string& path) : std::runtime_error(path + " exists (--skip-existing)") {}
};

/// The long names of the options that name outputs (a file for one input, a folder for several).
extern const std::vector<std::string> kOutputOptions;

/// The checks run_batch makes before any work (see the guide above), on the values of the kOutputOptions of
/// global.command (none when it is null) and on `files` (the expanded inputs). Creates output folders.
/// \throw InputError naming the option and the path, SkippedExisting.
void prepare_outputs(const std::vector<std::string>& files, bool batch, const GlobalOptions& global);

/// What one file of a batch produced.
struct FileResult {
  std::string input;
  int exit_code = kOk;   ///< 0 ok, 1 internal, 2 bad input, 3 partial result (stopped; outputs written)
  bool skipped = false;  ///< --skip-existing found an output of it (exit_code stays 0)
  std::string error;     ///< empty on success; otherwise the message main() would print (several lines allowed)
  double seconds = 0;
  nlohmann::json result;  ///< what the job returned (null on failure)
};

/// The work done for one input file; returns a JSON summary of the result.
using FileJob = std::function<nlohmann::json(const std::string& input, ProgressSink& progress)>;

struct BatchSpec {
  std::vector<std::string> inputs;           ///< as given: files and/or folders
  std::vector<std::string> summary_columns;  ///< keys of the job results shown in the summary table
};

/// Runs the job on every file, `jobs` at a time (0 = all cores) with TBB; exceptions are caught per file and turned
/// into FileResult::error / exit_code. Results are in input order whatever the scheduling (deterministic output).
/// Each finished file is reported on `log` (unless quiet). \pre none; the job's exceptions are caught per file.
std::vector<FileResult> process_files(const std::vector<std::string>& files, const GlobalOptions& global,
                                      const FileJob& job, std::ostream& log);

/// The summary table (text) or, with --json, {"files": [...], "succeeded": n, "skipped": s, "partial": p, "failed": m}
/// on `out`. \pre none
void print_summary(const std::vector<FileResult>& results, const std::vector<std::string>& columns,
                   const GlobalOptions& global, std::ostream& out);

/// Worst exit code of a batch: 2 if any bad input, else 1 if any other failure, else 3 if any partial result, else 0.
/// \pre none
int batch_exit_code(const std::vector<FileResult>& results);

/// One input: runs the job with a TerminalProgress on stderr (exceptions propagate) and prints its result
/// (JSON with --json, "key: value" lines otherwise, nothing with --quiet). Several: process_files + print_summary.
/// Returns the exit code. \throw InputError as expand_inputs / prepare_outputs; with one input, what the job throws.
int run_batch(const BatchSpec& spec, const GlobalOptions& global, const FileJob& job);

/// The work done for one input file of a command; `batch` is true when the command runs on several files or a
/// folder (is_batch of its inputs).
using InputJob = std::function<nlohmann::json(const std::string& input, bool batch, ProgressSink& progress)>;

/// Makes `cmd` run `job` on every one of `inputs` through run_batch when it is invoked, with `columns` (keys of
/// the job's JSON) in the summary table, and puts the exit code into `exit_code`.
/// \pre `inputs` (the command's option storage), `global` and `exit_code` outlive `cmd`.
void run_on_inputs(CLI::App& cmd, const GlobalOptions& global, int& exit_code, const std::vector<std::string>& inputs,
                   std::vector<std::string> columns, InputJob job);

/// Where the main output of `input` goes: `output` itself for one input, or, in a batch or when `output` is empty
/// (default: next to the input), batch_output_path(input, output, suffix). \throw as batch_output_path.
std::string output_path(const std::string& input, const std::string& output, bool batch, const std::string& suffix);

/// An optional output: empty when `output` is, `output` itself for one input, batch_output_path(input, output,
/// suffix) in a batch. \throw as batch_output_path.
std::string optional_output_path(const std::string& input, const std::string& output, bool batch,
                                 const std::string& suffix);

// ---- errors and outputs ---------------------------------------------------------------------------------------

/// Classifies the exception currently being handled (call inside catch (...)): returns the exit code and sets
/// `message` to what should be printed (one line per problem, without "error: "). \pre an exception is being handled.
int describe_current_exception(std::string& message);

/// Writes `j` (pretty-printed) atomically: no partial file on failure. \throw InputError if path cannot be written.
void write_json_atomically(const std::string& path, const nlohmann::json& j);

/// Prints a JSON object as "  key: value" lines (used for a single file's result without --json). \pre none
void print_key_values(const nlohmann::json& j, std::ostream& out);

}  // namespace quadcover::cli
