#include "cli/common.h"

#include <pthread.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "common/errors.h"
#include "common/seconds_since.h"
#include "io/atomic_file.h"
#include "io/read_mesh.h"
#include "io/weld_positions.h"
#include "mesh/degenerate_faces.h"

namespace quadcover::cli {

// ---- options ------------------------------------------------------------------------------------------------

void add_global_options(CLI::App& cmd, GlobalOptions& global) {
  cmd.add_flag("--json", global.json, "Print the result as JSON on stdout (batch: one document for all files)");
  cmd.add_flag("-q,--quiet", global.quiet, "Print nothing but errors and warnings (no progress, no result lines)");
  cmd.add_flag("-v,--verbose", global.verbose, "Print every progress report as its own line on stderr");
  cmd.add_option("--time-limit", global.time_limit,
                 "Whole-command time budget in SECONDS (default 0: no limit): Algorithm 6.1 stops early enough to "
                 "leave the later stages their estimated time; past the limit the stages that only improve a valid "
                 "result are skipped or cut short, the stages a valid result needs still finish, and the command "
                 "exits with 3 (partial result written) if anything was skipped")
      ->check(CLI::NonNegativeNumber);
  cmd.add_option("-j,--jobs", global.jobs, "Files processed at once in batch mode (default 0: all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd.add_flag("--overwrite-input", global.overwrite_input,
               "Allow an output to replace an input file (refused by default, also through a link or another name)");
  cmd.add_flag("--skip-existing", global.skip_existing,
               "Skip an input any of whose outputs exists already (default: existing outputs are replaced)");
  cmd.add_option("--format", global.format,
                 "Mesh format written to standard output by -o - (default obj); with -o -, the result lines go to "
                 "stderr. The mesh '-' (standard input) is recognized from its content")
      ->check(CLI::IsMember({"obj", "off", "ply", "stl"}));
  cmd.preparse_callback([&global, &cmd](std::size_t) { global.command = &cmd; });
}

const std::vector<std::string> kOutputOptions = {"--output", "--report", "--param", "--png", "--report-html", "--plot"};
/// Outputs of one input only (no batch folder for them), also never counted as inputs.
const std::vector<std::string> kSingleOutputOptions = {"--save-features"};

const char* const kBatchNamingHelp =
    "Several files or a folder run as a batch; outputs are named after the input's stem (a/bunny.obj -> "
    "bunny.<suffix>); inputs sharing an output name get their parent folder's name in front (a_bunny) and/or "
    "their extension appended (bunny_obj, bunny_off), then _2, _3, ... in input order. An existing output file is "
    "replaced (atomically: never half-written) unless --skip-existing; an input file is never replaced unless "
    "--overwrite-input; output folders are created";

void add_input_option(CLI::App& cmd, std::vector<std::string>& inputs, const std::string& description) {
  const CLI::Validator path_or_stdin([](std::string& s) { return s == "-" ? std::string() : CLI::ExistingPath(s); },
                                     "PATH or -");
  cmd.add_option("mesh", inputs, description + " ('-': standard input, see --format). " + kBatchNamingHelp)
      ->required()
      ->check(path_or_stdin);
}

void add_mesh_inputs(CLI::App& cmd, MeshFiles& files, const std::string& output_help, const std::string& input_help) {
  add_input_option(cmd, files.inputs, input_help);
  cmd.add_option("-o,--output", files.output, output_help);
}

// ---- cancellation -------------------------------------------------------------------------------------------

namespace {
std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the SIGINT handler needs a lock-free flag");

// Stop now: no temporary file may survive (only async-signal-safe calls here).
extern "C" void on_terminating_signal(int sig) {
  remove_temporary_files();
  ::_exit(128 + sig);
}

extern "C" void on_sigint(int sig) {
  if (g_interrupted.exchange(true)) on_terminating_signal(sig);  // a second Ctrl-C stops at once
}

// A crash: remove the temporary files, then let the signal do what it does by default (core dump, exit status).
extern "C" void on_crash_signal(int sig) {
  remove_temporary_files();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(undefined_behavior_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

void handle(int sig, void (*fn)(int)) {
  struct sigaction sa {};
  sa.sa_handler = fn;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(sig, &sa, nullptr);
}
}  // namespace

void install_interrupt_handler() {
  handle(SIGINT, on_sigint);
  for (int sig : {SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGUSR1, SIGUSR2, SIGALRM, SIGXCPU, SIGXFSZ, SIGVTALRM})
    handle(sig, on_terminating_signal);
  if (!kSanitized)  // the sanitizers report crashes through their own handlers
    for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) handle(sig, on_crash_signal);
}

int run_watching_signals(const std::function<int()>& job) {
  sigset_t watched;
  sigemptyset(&watched);
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGXCPU})
    sigaddset(&watched, sig);
  const int job_done = SIGRTMIN;  // sent by the job's thread when it returns
  sigaddset(&watched, job_done);
  if (pthread_sigmask(SIG_BLOCK, &watched, nullptr) != 0) return job();
  const pthread_t watcher = pthread_self();
  int code = kInternal;
  std::thread worker([&] {
    code = job();
    pthread_kill(watcher, job_done);
  });
  for (int sig = 0; sig != job_done;) {
    if (sigwait(&watched, &sig) != 0 || sig == job_done) continue;
    (sig == SIGINT ? on_sigint : on_terminating_signal)(sig);  // as the handlers do
  }
  worker.join();
  return code;
}

bool interrupted() { return g_interrupted.load(); }
void request_interrupt() { g_interrupted.store(true); }
void clear_interrupt() { g_interrupted.store(false); }

std::chrono::steady_clock::time_point run_start_time() {
  static const auto start = std::chrono::steady_clock::now();
  return start;
}

std::mutex& stderr_mutex() {
  static std::mutex m;
  return m;
}

void warn(ProgressSink& progress, const std::string& text) { progress.report("warning", -1, "warning: " + text); }

namespace {

// The soup of `input`; for a new surface its polygons fan-triangulated, said through `progress`.
PolygonSoup read_soup(const std::string& input, const std::string& name, bool new_surface, ProgressSink& progress) {
  PolygonSoup soup = read_mesh(input);
  std::size_t polygons = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) polygons += soup.face_size(f) > 3;
  if (!new_surface || polygons == 0) return soup;
  soup = triangulate_polygons(soup);
  warn(progress, name + ": " + std::to_string(polygons) +
                     " polygons (faces of more than 3 corners) split into triangles from their first corner");
  return soup;
}

// For a new surface (`remesh`): the mesh of `soup` with its vertices at one point welded (io/weld_positions.h:
// `welding`) and repaired (build_repaired: `removed`); when the welded surface is not a valid manifold (pieces that
// touch at a point), the same without the welding (welding.merged 0). Each change said through `progress`.
// \throw as build_mesh(soup).
MeshBuildResult build_new_surface(const PolygonSoup& soup, const std::string& name, Welding& welding,
                                  DegenerateFaceRemoval& removed, ProgressSink& progress) {
  PolygonSoup joined = soup;
  welding = weld_identical_positions(joined);
  std::optional<MeshBuildResult> built;
  if (welding.merged > 0) {
    try {
      built = build_repaired(std::move(joined), removed);
      warn(progress, name + ": " + std::to_string(welding.merged) + " vertices at the position of an earlier vertex " +
                         "merged into it (the file's surface is cut there, as exporters split vertices at texture " +
                         "seams)");
    } catch (const TopologyError&) {
      const std::size_t apart = welding.merged;
      welding = {};
      built = build_repaired(soup, removed);
      warn(progress, name + ": " + std::to_string(apart) + " vertices at the position of another are not merged: " +
                         "merged, the surface would not be a manifold");
    }
  }
  if (!built) built = build_repaired(soup, removed);
  if (removed.total() > 0)
    warn(progress, name + ": " + std::to_string(removed.total()) + " zero-area triangles that carry no surface " +
                       "removed (repeated vertices or faces, corners on an opposite edge or at one point; see " +
                       "quadcover repair)");
  if (built->report.flipped_faces > 0)
    warn(progress, name + ": " + std::to_string(built->report.flipped_faces) +
                       " faces turned to the orientation of their neighbours");
  return std::move(*built);
}

Mesh load_mesh(const std::string& input, ProgressSink& progress, FileVertices* file_vertices, bool written_back,
               bool new_surface) {
  const std::string name = input == "-" ? std::string("<stdin>") : input;
  const PolygonSoup soup = read_soup(input, name, new_surface, progress);
  Welding welding;
  DegenerateFaceRemoval removed;
  MeshBuildResult built = new_surface ? build_new_surface(soup, name, welding, removed, progress) : build_mesh(soup);
  const std::size_t dropped = built.report.unreferenced_vertices - welding.merged - removed.merged_needles;
  if (dropped > 0 && written_back)
    warn(progress, name + ": " + std::to_string(dropped) +
                       " unreferenced vertices (used by no face) are written back unchanged, without texture "
                       "coordinates, so the output keeps the input's vertex numbers");
  else if (dropped > 0)
    warn(progress, name + ": " + std::to_string(dropped) + " unreferenced vertices (used by no face) dropped: the " +
                       "outputs number the " + std::to_string(built.mesh.num_vertices()) + " others in input " +
                       "order, so vertex numbers after the first dropped one differ from the input's");
  if (file_vertices) {
    if (written_back) file_vertices->positions = soup.positions;
    file_vertices->mesh_of = built.vertex_map;
    for (std::size_t v = 0; v < welding.into.size(); ++v)  // a merged vertex is where it was merged into
      if (file_vertices->mesh_of[v] < 0 && welding.into[v] != static_cast<std::int64_t>(v))
        file_vertices->mesh_of[v] = built.vertex_map[static_cast<std::size_t>(welding.into[v])];
    file_vertices->of_mesh.assign(static_cast<std::size_t>(built.mesh.num_vertices()), -1);
    for (std::size_t v = 0; v < built.vertex_map.size(); ++v)
      if (built.vertex_map[v] >= 0)
        file_vertices->of_mesh[static_cast<std::size_t>(built.vertex_map[v])] = static_cast<int>(v);
  }
  return std::move(built.mesh);
}

}  // namespace

MeshBuildResult build_repaired(PolygonSoup soup, DegenerateFaceRemoval& removed) {
  ValidationOptions options;
  options.triangulate = true;
  options.fix_orientation = true;
  removed = remove_degenerate_faces(soup, options.degenerate_tolerance);
  return build_mesh(soup, options);
}

Mesh load_mesh(const std::string& input, ProgressSink& progress) {
  return load_mesh(input, progress, nullptr, false, false);
}

Mesh load_mesh(const std::string& input, ProgressSink& progress, FileVertices& file_vertices, bool written_back,
               bool new_surface) {
  return load_mesh(input, progress, &file_vertices, written_back, new_surface);
}

// ---- progress -----------------------------------------------------------------------------------------------

ProgressStyle stderr_progress_style(const GlobalOptions& global) {
  ProgressStyle style;
  style.quiet = global.quiet;
  style.verbose = global.verbose;
  style.live = !global.verbose && ::isatty(STDERR_FILENO) != 0;
  if (style.live) {
    winsize ws{};
    if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 20) style.width = ws.ws_col - 1;
    style.delay = 0.3;
  }
  if (global.verbose) style.delay = style.interval = 0;
  return style;
}

TerminalProgress::TerminalProgress(std::ostream& out, ProgressStyle style, Clock::time_point deadline)
    : out_(out),
      style_(std::move(style)),
      deadline_(deadline),
      start_(Clock::now()),
      stage_start_(start_),
      last_print_(start_ - std::chrono::hours(1)) {}

namespace {
TerminalProgress::Clock::time_point deadline_for(const GlobalOptions& global) {
  if (global.time_limit <= 0) return TerminalProgress::Clock::time_point::max();
  return run_start_time() + std::chrono::duration_cast<TerminalProgress::Clock::duration>(
                                std::chrono::duration<double>(global.time_limit));
}
}  // namespace

TerminalProgress::TerminalProgress(const GlobalOptions& global)
    : TerminalProgress(std::cerr, stderr_progress_style(global), deadline_for(global)) {}

TerminalProgress::~TerminalProgress() { finish(); }

void TerminalProgress::finish() {
  std::lock_guard lock(mutex_);
  if (live_dirty_) {
    std::lock_guard err_lock(stderr_mutex());
    out_ << "\r\x1b[K" << std::flush;
    live_dirty_ = false;
  }
}

std::string TerminalProgress::format_line(std::string_view stage, double fraction, std::string_view message,
                                          double eta_seconds, bool bar, int width) {
  std::ostringstream s;
  s << stage;
  const bool known = fraction >= 0;
  const double f = std::clamp(fraction, 0.0, 1.0);
  if (bar) {
    constexpr int kBar = 24;
    s << " [";
    if (known) {
      const int filled = static_cast<int>(std::lround(f * kBar));
      s << std::string(filled, '=') << std::string(kBar - filled, ' ');
    } else {
      s << std::string(kBar / 2 - 1, ' ') << "..." << std::string(kBar - kBar / 2 - 2, ' ');
    }
    s << "]";
  }
  if (known) s << ' ' << std::setw(3) << static_cast<int>(std::floor(f * 100)) << '%';
  if (!message.empty()) s << "  " << message;
  if (known && eta_seconds >= 0 && f < 1) {
    s << "  ETA ";
    if (eta_seconds < 60)
      s << static_cast<int>(std::ceil(eta_seconds)) << 's';
    else
      s << static_cast<int>(eta_seconds / 60) << 'm' << std::setw(2) << std::setfill('0')
        << static_cast<int>(eta_seconds) % 60 << 's';
  }
  std::string line = s.str();
  if (width > 0 && static_cast<int>(line.size()) > width) line.resize(static_cast<std::size_t>(width));
  return line;
}

void TerminalProgress::report(std::string_view stage, double fraction, std::string_view message) {
  if (message.starts_with("warning: ")) {  // shown at once, on its own line, whatever the mode, the delay and -q
    std::lock_guard lock(mutex_);
    std::lock_guard err_lock(stderr_mutex());
    out_ << (live_dirty_ ? "\r\x1b[K" : "") << style_.prefix << message << '\n' << std::flush;
    live_dirty_ = false;
    return;
  }
  if (style_.quiet) return;
  std::lock_guard lock(mutex_);
  const Clock::time_point now = Clock::now();
  const bool new_stage = stage != stage_;
  if (new_stage) {
    stage_ = std::string(stage);
    stage_start_ = now;
  }
  const double since_start = std::chrono::duration<double>(now - start_).count();
  if (since_start < style_.delay) return;
  const double since_print = std::chrono::duration<double>(now - last_print_).count();
  const double interval = style_.live ? 0.1 : style_.interval;
  const bool stage_done = fraction >= 1;
  if (!style_.verbose && since_print < interval && !(new_stage && style_.live) && !(stage_done && style_.live)) return;
  last_print_ = now;
  const double elapsed = std::chrono::duration<double>(now - stage_start_).count();
  const double eta = fraction > 0 && fraction < 1 ? elapsed * (1 - fraction) / fraction : -1;
  std::lock_guard err_lock(stderr_mutex());
  if (style_.live) {
    const int width = style_.width - static_cast<int>(style_.prefix.size());
    out_ << "\r\x1b[K" << style_.prefix << format_line(stage, fraction, message, eta, true, width) << std::flush;
    live_dirty_ = true;
  } else {
    out_ << style_.prefix << format_line(stage, fraction, message, eta, false, 0) << '\n' << std::flush;
  }
  printed_any_ = true;
}

double TerminalProgress::seconds_left() const {
  if (deadline_ == Clock::time_point::max()) return ProgressSink::seconds_left();
  return std::chrono::duration<double>(deadline_ - Clock::now()).count();
}

bool TerminalProgress::cancelled() const {
  const bool by_signal = interrupted();
  const bool by_time = deadline_ != Clock::time_point::max() && Clock::now() >= deadline_;
  if ((by_signal || by_time) && !announced_stop_ && !style_.quiet) {
    std::lock_guard lock(mutex_);
    if (!announced_stop_) {
      announced_stop_ = true;
      std::lock_guard err_lock(stderr_mutex());
      out_ << (live_dirty_ ? "\n" : "") << style_.prefix << (by_signal ? "interrupted" : "time limit reached")
           << ": stopping with the best result so far\n"
           << std::flush;
    }
  }
  return by_signal || by_time;
}

// ---- batch --------------------------------------------------------------------------------------------------

namespace {
bool is_mesh_file(const std::filesystem::path& p) {
  const std::string ext = file_extension(p.string());
  return ext == "obj" || ext == "off" || ext == "ply" || ext == "stl";
}

// The files of the batch being processed (set by process_files), so that batch_output_path can tell which other
// inputs share an output name. Written before the workers start, read by them.
std::mutex g_batch_mutex;
std::atomic<bool> g_skip_existing{false};  // --skip-existing of the command being run (set by run_batch)
std::vector<std::string> g_batch_files;
std::map<std::string, std::vector<std::string>> g_batch_stems;  // batch_output_stems per output folder

std::string normal_path(const std::filesystem::path& p) {
  std::error_code ec;
  const std::filesystem::path a = std::filesystem::absolute(p, ec);
  return (ec ? p : a).lexically_normal().string();
}

// The name of the folder holding `input` ("" at the root).
std::string parent_name(const std::string& input) {
  return std::filesystem::path(normal_path(input)).parent_path().filename().string();
}

}  // namespace

std::vector<std::string> expand_inputs(const std::vector<std::string>& args) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  for (const std::string& arg : args) {
    if (arg == "-") {
      if (args.size() > 1) throw InputError("-", 0, "standard input ('-') is for one mesh only, not in a batch");
      files.push_back(arg);
      continue;
    }
    std::error_code ec;
    const fs::file_status st = fs::status(arg, ec);
    if (ec || !fs::exists(st)) throw InputError(arg, 0, "no such file or folder");
    if (fs::is_directory(st)) {
      std::vector<std::string> found;
      for (const auto& entry : fs::directory_iterator(arg, ec))
        if (entry.is_regular_file() && is_mesh_file(entry.path())) found.push_back(entry.path().string());
      if (ec) throw InputError(arg, 0, "cannot list folder: " + ec.message());
      if (found.empty()) throw InputError(arg, 0, "folder holds no mesh files (.obj .off .ply .stl)");
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else {
      files.push_back(arg);
    }
  }
  // A file named twice (also as "./a.obj" and "a.obj", or in a folder and by name) is processed once.
  std::set<std::string> seen;
  std::erase_if(files, [&](const std::string& f) { return !seen.insert(normal_path(f)).second; });
  return files;
}

bool is_batch(const std::vector<std::string>& args) {
  return args.size() > 1 || (args.size() == 1 && std::filesystem::is_directory(args[0]));
}

std::vector<std::string> batch_output_stems(const std::vector<std::string>& files, const std::string& output_dir) {
  namespace fs = std::filesystem;
  const std::size_t n = files.size();
  // The output folder of each file ("" for the common output_dir) and its stem (rule 1).
  std::vector<std::string> folder(n), stems(n), names(n);
  std::map<std::pair<std::string, std::string>, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < n; ++i) {
    const fs::path in(files[i]);
    folder[i] = output_dir.empty() ? normal_path(in.parent_path()) : std::string();
    names[i] = stems[i] = in.stem().string();
    groups[{folder[i], stems[i]}].push_back(i);
  }
  // Rules 2 and 3: within a group of files whose outputs share folder and stem, add what tells them apart.
  for (const auto& [key, group] : groups) {
    if (group.size() < 2) continue;
    const std::size_t first = group.front();
    bool folders_differ = false, extensions_differ = false;
    for (std::size_t k : group) {
      folders_differ |= parent_name(files[k]) != parent_name(files[first]);
      extensions_differ |= fs::path(files[k]).extension() != fs::path(files[first]).extension();
    }
    for (std::size_t k : group) {
      const std::string parent = parent_name(files[k]);
      std::string ext = fs::path(files[k]).extension().string();
      if (!ext.empty()) ext.erase(0, 1);
      if (folders_differ && !parent.empty()) names[k] = parent + "_" + names[k];
      if (extensions_differ && !ext.empty()) names[k] += "_" + ext;
    }
  }
  // Rule 4: a name still taken (same folder name and extension, or a name made above that another input has as
  // its own) gets _2, _3, ... in input order. Unchanged names are reserved first, so a renamed file never takes
  // another input's plain name.
  std::set<std::pair<std::string, std::string>> taken;
  std::vector<std::string> result(n);
  for (std::size_t i = 0; i < n; ++i)
    if (names[i] == stems[i] && taken.insert({folder[i], names[i]}).second) result[i] = names[i];
  for (std::size_t i = 0; i < n; ++i) {
    if (!result[i].empty()) continue;
    std::string name = names[i];
    for (int copy = 2; !taken.insert({folder[i], name}).second; ++copy) name = names[i] + "_" + std::to_string(copy);
    result[i] = name;
  }
  return result;
}

std::string batch_output_path(const std::string& input, const std::string& output_dir, const std::string& suffix) {
  namespace fs = std::filesystem;
  if (input == "-" && output_dir.empty()) return "-";  // standard input: the output goes to standard output
  const fs::path in(input);
  const fs::path dir = output_dir.empty() ? in.parent_path() : fs::path(output_dir);
  std::string stem = in.stem().string();
  {
    std::lock_guard lock(g_batch_mutex);
    const auto it = std::find(g_batch_files.begin(), g_batch_files.end(), input);
    if (it != g_batch_files.end()) {
      auto cached = g_batch_stems.find(output_dir);
      if (cached == g_batch_stems.end())
        cached = g_batch_stems.emplace(output_dir, batch_output_stems(g_batch_files, output_dir)).first;
      stem = cached->second[static_cast<std::size_t>(it - g_batch_files.begin())];
    }
  }
  const std::string path = (dir / (stem + suffix)).string();
  if (g_skip_existing.load() && fs::exists(path)) throw SkippedExisting(path);
  check_output_guard(path);  // an output that is an input fails now, before the work
  return path;
}

std::string output_path(const std::string& input, const std::string& output, bool batch, const std::string& suffix) {
  return batch || output.empty() ? batch_output_path(input, output, suffix) : output;
}

std::string optional_output_path(const std::string& input, const std::string& output, bool batch,
                                 const std::string& suffix) {
  return output.empty() ? std::string() : batch ? batch_output_path(input, output, suffix) : output;
}

int describe_current_exception(std::string& message) {
  try {
    throw;
  } catch (const InputError& e) {
    message = e.what();
    return kBadInput;
  } catch (const TopologyError& e) {
    message = e.what();
    for (const auto& p : e.problems()) message += "\n  " + p;
    return kBadInput;
  } catch (const std::exception& e) {
    message = e.what();
    return kInternal;
  } catch (...) {
    message = "unknown error";
    return kInternal;
  }
}

std::vector<FileResult> process_files(const std::vector<std::string>& files, const GlobalOptions& global,
                                      const FileJob& job, std::ostream& log) {
  // While the batch runs, batch_output_path names its outputs apart (batch_output_stems); cleared on every exit.
  struct BatchNames {
    explicit BatchNames(const std::vector<std::string>& files) { set(files); }
    ~BatchNames() { set({}); }
    static void set(const std::vector<std::string>& files) {
      std::lock_guard lock(g_batch_mutex);
      g_batch_stems.clear();
      g_batch_files = files;
    }
  } const batch_names(files);
  std::vector<FileResult> results(files.size());
  std::atomic<int> done{0};
  const int threads =
      global.jobs > 0 ? global.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::size_t width = [&] {
    std::size_t w = 0;
    for (const auto& f : files) w = std::max(w, f.size());
    return w;
  }();
  auto run_one = [&](std::size_t i) {
    FileResult& r = results[i];
    r.input = files[i];
    ProgressStyle style;
    style.quiet = global.quiet || !global.verbose;  // batch: per-file progress only with --verbose
    style.verbose = global.verbose;
    style.delay = style.interval = 0;
    style.prefix = files[i] + ": ";
    TerminalProgress progress(log, style,
                              global.time_limit > 0
                                  ? run_start_time() + std::chrono::duration_cast<TerminalProgress::Clock::duration>(
                                                           std::chrono::duration<double>(global.time_limit))
                                  : TerminalProgress::Clock::time_point::max());
    const auto t0 = std::chrono::steady_clock::now();
    if (interrupted()) {
      r.exit_code = kInternal;
      r.error = "not started: interrupted";
    } else {
      try {
        r.result = job(files[i], progress);
        r.exit_code = result_exit_code(r.result);
      } catch (const SkippedExisting& e) {
        r.skipped = true;
        r.error = e.what();
      } catch (...) {
        r.exit_code = describe_current_exception(r.error);
      }
    }
    r.seconds = seconds_since(t0);
    const int n = ++done;
    const bool failed = !r.skipped && r.exit_code != kOk && r.exit_code != kPartial;
    if (global.quiet && failed) {  // -q hides the progress lines, never an error
      std::lock_guard lock(stderr_mutex());
      const bool named = r.error.rfind(files[i], 0) == 0;
      log << "error: " << (named ? "" : files[i] + ": ") << r.error << '\n' << std::flush;
    } else if (!global.quiet) {
      std::lock_guard lock(stderr_mutex());
      log << '[' << n << '/' << files.size() << "] " << std::left << std::setw(static_cast<int>(width)) << files[i]
          << std::right
          << (r.skipped                 ? "  skipped  "
              : r.exit_code == kOk      ? "  ok  "
              : r.exit_code == kPartial ? "  partial  "
                                        : "  FAILED  ")
          << std::fixed << std::setprecision(2) << r.seconds << " s" << std::defaultfloat << '\n';
      if (r.exit_code != kOk && r.exit_code != kPartial) log << "  error: " << r.error << '\n';
      if (r.skipped) log << "  " << r.error << '\n';
      log << std::flush;
    }
  };
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(
        std::size_t{0}, files.size(), [&](std::size_t i) { run_one(i); }, tbb::simple_partitioner());
  });
  return results;
}

namespace {
std::string cell(const nlohmann::json& v) {
  if (v.is_null()) return "-";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) {
    std::ostringstream s;
    s << std::setprecision(4) << v.get<double>();
    return s.str();
  }
  return v.dump();
}
}  // namespace

void print_summary(const std::vector<FileResult>& results, const std::vector<std::string>& columns,
                   const GlobalOptions& global, std::ostream& out) {
  int failed = 0, skipped = 0, partial = 0;
  for (const auto& r : results) {
    failed += r.exit_code != kOk && r.exit_code != kPartial;
    partial += r.exit_code == kPartial;
    skipped += r.skipped;
  }
  if (global.json) {
    nlohmann::json files = nlohmann::json::array();
    for (const auto& r : results) {
      nlohmann::json j{
          {"file", r.input}, {"ok", r.exit_code == kOk}, {"exit_code", r.exit_code}, {"seconds", r.seconds}};
      if (r.skipped) {
        j["skipped"] = r.error;
      } else if (r.exit_code == kOk || r.exit_code == kPartial) {
        j["result"] = r.result;
      } else {
        j["error"] = r.error;
      }
      files.push_back(std::move(j));
    }
    out << nlohmann::json{{"files", files},
                          {"succeeded", static_cast<int>(results.size()) - failed - skipped - partial},
                          {"skipped", skipped},
                          {"partial", partial},
                          {"failed", failed}}
               .dump(2)
        << '\n';
    return;
  }
  if (global.quiet) return;
  std::vector<std::string> header{"file", "status", "seconds"};
  header.insert(header.end(), columns.begin(), columns.end());
  std::vector<std::vector<std::string>> rows;
  for (const auto& r : results) {
    std::ostringstream secs;
    secs << std::fixed << std::setprecision(2) << r.seconds;
    std::vector<std::string> row{r.input,
                                 r.skipped            ? "skipped"
                                 : r.exit_code == kOk      ? "ok"
                                 : r.exit_code == kPartial ? "partial"
                                                           : (r.exit_code == kBadInput ? "bad input" : "failed"),
                                 secs.str()};
    for (const auto& c : columns)
      row.push_back(r.result.is_object() && r.result.contains(c) ? cell(r.result[c]) : "-");
    rows.push_back(std::move(row));
  }
  std::vector<std::size_t> w(header.size());
  for (std::size_t c = 0; c < header.size(); ++c) {
    w[c] = header[c].size();
    for (const auto& row : rows) w[c] = std::max(w[c], row[c].size());
  }
  auto print_row = [&](const std::vector<std::string>& row) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (c) out << "  ";
      if (c == 0)
        out << std::left << std::setw(static_cast<int>(w[c])) << row[c] << std::right;
      else
        out << std::setw(static_cast<int>(w[c])) << row[c];
    }
    out << '\n';
  };
  print_row(header);
  std::size_t total = 2 * (w.size() - 1);
  for (auto x : w) total += x;
  out << std::string(total, '-') << '\n';
  for (const auto& row : rows) print_row(row);
  out << results.size() - failed - skipped - partial << " of " << results.size() << " files succeeded";
  if (skipped) out << ", " << skipped << " skipped (--skip-existing)";
  if (partial) out << ", " << partial << " partial (stopped by Ctrl-C or --time-limit)";
  if (failed) out << ", " << failed << " failed";
  out << '\n';
}

int batch_exit_code(const std::vector<FileResult>& results) {
  int code = kOk;
  for (const auto& r : results) {
    if (r.exit_code == kBadInput) return kBadInput;
    if (r.exit_code == kInternal || code == kOk) code = r.exit_code;
  }
  return code;
}

void print_key_values(const nlohmann::json& j, std::ostream& out) {
  if (!j.is_object()) {
    if (!j.is_null()) out << j.dump() << '\n';
    return;
  }
  for (const auto& [key, value] : j.items()) out << "  " << key << ": " << cell(value) << '\n';
}

namespace {
// A file's identity: the same (device, inode) is the same file under any name or link.
struct FileId {
  dev_t dev;
  ino_t ino;
  bool operator==(const FileId&) const = default;
};

std::optional<FileId> file_id(const std::string& path) {
  struct stat st {};
  if (path == "-" || ::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
  return FileId{st.st_dev, st.st_ino};
}

// The files a run reads: the mesh inputs and every other option's value that names an existing file (--ref, ...).
std::vector<std::pair<FileId, std::string>> protected_inputs(const std::vector<std::string>& files,
                                                             const GlobalOptions& global) {
  std::vector<std::pair<FileId, std::string>> inputs;
  auto add = [&](const std::string& path) {
    if (const auto id = file_id(path)) inputs.emplace_back(*id, path);
  };
  for (const auto& f : files) add(f);
  if (global.command)
    for (const CLI::Option* o : global.command->get_options()) {
      const std::string name = "--" + o->get_single_name();
      if (std::find(kOutputOptions.begin(), kOutputOptions.end(), name) != kOutputOptions.end() ||
          std::find(kSingleOutputOptions.begin(), kSingleOutputOptions.end(), name) != kSingleOutputOptions.end())
        continue;
      for (const auto& value : o->results()) add(value);
    }
  return inputs;
}

void refuse_if_input(const std::string& path, const std::vector<std::pair<FileId, std::string>>& inputs) {
  const auto id = file_id(path);
  if (!id) return;
  for (const auto& [input_id, input] : inputs)
    if (input_id == *id)
      throw InputError(path, 0,
                       "refusing to replace the input file " + input +
                           (path == input ? std::string() : " (the same file under another name)") +
                           ": name another output, or pass --overwrite-input");
}

// The output folder `dir` exists (created if needed) and can be written to.
void prepare_folder(const std::string& option, const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  const fs::path d = dir.empty() ? fs::path(".") : dir;
  std::error_code ec;
  if (fs::exists(d, ec) && !fs::is_directory(d, ec))
    throw InputError(d.string(), 0, option + ": this is a file, but a folder is needed here");
  fs::create_directories(d, ec);
  if (ec) throw InputError(d.string(), 0, option + ": cannot create the output folder: " + ec.message());
  if (::access(d.c_str(), W_OK | X_OK) != 0)
    throw InputError(d.string(), 0, option + ": the output folder is not writable");
}

// The guard every write_file_atomically asks while run_batch runs; removed on every exit.
struct GuardScope {
  GuardScope(std::vector<std::pair<FileId, std::string>> inputs, const GlobalOptions& global) {
    g_skip_existing = global.skip_existing;
    if (!global.overwrite_input)
      set_output_guard([inputs = std::move(inputs)](const std::string& path) { refuse_if_input(path, inputs); });
  }
  ~GuardScope() {
    set_output_guard({});
    g_skip_existing = false;
  }
  GuardScope(const GuardScope&) = delete;
  GuardScope& operator=(const GuardScope&) = delete;
};
}  // namespace

void prepare_outputs(const std::vector<std::string>& files, bool batch, const GlobalOptions& global) {
  namespace fs = std::filesystem;
  if (!global.command) return;
  const auto inputs = protected_inputs(files, global);
  for (const std::string& name : kOutputOptions) {
    const CLI::Option* o = global.command->get_option_no_throw(name);
    if (!o || o->count() == 0) continue;
    for (const std::string& value : o->results()) {
      if (value.empty()) continue;
      if (value == "-") {
        if (batch) throw InputError("-", 0, name + " -: standard output takes the output of one input only");
        continue;
      }
      if (batch) {
        prepare_folder(name, value);
        continue;
      }
      std::error_code ec;
      if (fs::is_directory(value, ec))
        throw InputError(value, 0, name + ": this is a folder; with one input, " + name + " names the output file");
      if (!global.overwrite_input) refuse_if_input(value, inputs);
      prepare_folder(name, fs::path(value).parent_path());
      if (global.skip_existing && fs::exists(value, ec)) throw SkippedExisting(value);
    }
  }
}

int run_batch(const BatchSpec& spec, const GlobalOptions& global, const FileJob& job) {
  set_standard_stream_format(global.format);
  const bool batch = is_batch(spec.inputs);
  const std::vector<std::string> files = expand_inputs(spec.inputs);
  const GuardScope guard(protected_inputs(files, global), global);
  if (!batch) {
    nlohmann::json result;
    try {
      prepare_outputs(files, false, global);
      TerminalProgress progress(global);
      result = job(files.at(0), progress);
    } catch (const SkippedExisting& e) {
      if (!global.quiet) std::cerr << "skipped: " << e.what() << '\n';
      return kOk;
    }
    // Standard output holds the mesh: the result lines go to stderr then.
    std::ostream& out = wrote_standard_output() ? std::cerr : std::cout;
    if (global.json)
      out << result.dump(2) << '\n';
    else if (!global.quiet)
      print_key_values(result, out);
    return result_exit_code(result);
  }
  prepare_outputs(files, true, global);
  const std::vector<FileResult> results = process_files(files, global, job, std::cerr);
  print_summary(results, spec.summary_columns, global, std::cout);
  return batch_exit_code(results);
}

void run_on_inputs(CLI::App& cmd, const GlobalOptions& global, int& exit_code, const std::vector<std::string>& inputs,
                   std::vector<std::string> columns, InputJob job) {
  cmd.callback([&global, &exit_code, &inputs, columns = std::move(columns), job = std::move(job)] {
    BatchSpec spec;
    spec.inputs = inputs;
    spec.summary_columns = columns;
    const bool batch = is_batch(inputs);
    exit_code = run_batch(spec, global, [&job, batch](const std::string& input, ProgressSink& progress) {
      return job(input, batch, progress);
    });
  });
}

void write_json_atomically(const std::string& path, const nlohmann::json& j) {
  write_file_atomically(path, [&](std::ostream& out) { out << j.dump(2) << '\n'; });
}

}  // namespace quadcover::cli
