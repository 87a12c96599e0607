// The shared CLI machinery (cli/common.h): progress lines, cancellation, batch processing with failing files,
// summary output and atomic JSON.
#include "cli/common.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "calculus/sparse_cholesky.h"
#include "common/errors.h"
#include "io/atomic_file.h"
#include "support/cli_runner.h"
#include "support/grid_matrix.h"
#include "support/test_meshes.h"

namespace quadcover::cli {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) { return quadcover::testing::fresh_dir("cli_test", name); }

TEST(ProgressLine, PlainLineShowsStagePercentMessageAndEta) {
  const std::string line = TerminalProgress::format_line("optimize", 0.25, "iteration 3, E_D 1.5", 12.2, false, 0);
  EXPECT_EQ(line, "optimize  25%  iteration 3, E_D 1.5  ETA 13s");
}

TEST(ProgressLine, BarFillsProportionallyAndIsTruncatedToWidth) {
  const std::string half = TerminalProgress::format_line("s", 0.5, "", -1, true, 0);
  EXPECT_EQ(std::count(half.begin(), half.end(), '='), 12);
  const std::string full = TerminalProgress::format_line("s", 1.0, "", -1, true, 0);
  EXPECT_EQ(std::count(full.begin(), full.end(), '='), 24);
  EXPECT_NE(full.find("100%"), std::string::npos);
  EXPECT_EQ(TerminalProgress::format_line("stage", 0.5, std::string(200, 'x'), 5, true, 40).size(), 40u);
  // Unknown fraction: no percentage, no ETA.
  const std::string unknown = TerminalProgress::format_line("field", -1, "smoothing", 5, false, 0);
  EXPECT_EQ(unknown, "field  smoothing");
  EXPECT_NE(TerminalProgress::format_line("s", 0.1, "", 125, false, 0).find("ETA 2m05s"), std::string::npos);
}

TEST(TerminalProgress, VerbosePrintsEveryReportAsALine) {
  std::ostringstream out;
  ProgressStyle style;
  style.verbose = true;
  style.delay = style.interval = 0;
  style.prefix = "[a] ";
  {
    TerminalProgress p(out, style);
    p.report("field", 0.5, "half");
    p.report("field", 1.0, "done");
    p.report("param", 0.0, "");
  }
  std::istringstream lines(out.str());
  std::vector<std::string> got;
  for (std::string l; std::getline(lines, l);) got.push_back(l);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0].rfind("[a] field  50%  half", 0), 0u);
  EXPECT_EQ(got[1], "[a] field 100%  done");
  EXPECT_EQ(got[2].rfind("[a] param   0%", 0), 0u);
}

TEST(TerminalProgress, QuickRunsStaySilentAndPlainModeIsThrottled) {
  std::ostringstream silent;
  ProgressStyle style;  // defaults: nothing in the first second, then at most a line per second
  {
    TerminalProgress p(silent, style);
    for (int i = 0; i < 100; ++i) p.report("stage", i / 100.0, "");
  }
  EXPECT_TRUE(silent.str().empty());

  std::ostringstream throttled;
  style.delay = 0;
  style.interval = 3600;
  {
    TerminalProgress p(throttled, style);
    for (int i = 0; i < 100; ++i) p.report("stage", i / 100.0, "");
  }
  const std::string text = throttled.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
}

TEST(TerminalProgress, LiveModeRedrawsOneLineAndClearsIt) {
  std::ostringstream out;
  ProgressStyle style;
  style.live = true;
  style.delay = 0;
  style.width = 60;
  {
    TerminalProgress p(out, style);
    p.report("remesh", 0.3, "tracing");
  }
  const std::string s = out.str();
  EXPECT_EQ(s.find('\n'), std::string::npos);
  EXPECT_NE(s.find("remesh ["), std::string::npos);
  EXPECT_EQ(s.substr(s.size() - 4), "\r\x1b[K");  // finish() erased the bar
}

TEST(Cancellation, InterruptFlagAndDeadlineCancel) {
  std::ostringstream out;
  ProgressStyle style;
  clear_interrupt();
  {
    TerminalProgress p(out, style);
    EXPECT_FALSE(p.cancelled());
    request_interrupt();
    EXPECT_TRUE(p.cancelled());
    EXPECT_TRUE(p.cancelled());
    clear_interrupt();
    EXPECT_FALSE(p.cancelled());
  }
  EXPECT_NE(out.str().find("interrupted: stopping with the best result so far"), std::string::npos);
  // Announced once only.
  EXPECT_EQ(out.str().find("interrupted", out.str().find("interrupted") + 1), std::string::npos);

  std::ostringstream out2;
  TerminalProgress expired(out2, style, TerminalProgress::Clock::now() - std::chrono::seconds(1));
  EXPECT_TRUE(expired.cancelled());
  EXPECT_NE(out2.str().find("time limit reached"), std::string::npos);
  TerminalProgress later(out2, style, TerminalProgress::Clock::now() + std::chrono::hours(1));
  EXPECT_FALSE(later.cancelled());
}

TEST(Batch, ExpandInputsListsMeshFilesOfFoldersSorted) {
  const fs::path dir = fresh_dir("expand");
  for (const char* name : {"b.obj", "a.OFF", "notes.txt", "c.stl"}) std::ofstream(dir / name) << "\n";
  fs::create_directories(dir / "sub.obj");  // a folder, even with a mesh-like name, is not a file
  const std::vector<std::string> files = expand_inputs({(dir / "c.stl").string(), dir.string()});
  ASSERT_EQ(files.size(), 3u);  // c.stl, named again by its folder, is kept once at its first place
  EXPECT_EQ(fs::path(files[0]).filename(), "c.stl");
  EXPECT_EQ(fs::path(files[1]).filename(), "a.OFF");
  EXPECT_EQ(fs::path(files[2]).filename(), "b.obj");
  EXPECT_TRUE(is_batch({dir.string()}));
  EXPECT_FALSE(is_batch({(dir / "b.obj").string()}));
  EXPECT_THROW(expand_inputs({(dir / "missing.obj").string()}), InputError);
  const fs::path empty = fresh_dir("expand_empty");
  EXPECT_THROW(expand_inputs({empty.string()}), InputError);
  fs::remove_all(dir);
  fs::remove_all(empty);
}

TEST(Batch, OutputPathGoesIntoOutputFolderWithSuffix) {
  EXPECT_EQ(batch_output_path("meshes/bunny.obj", "out", ".quad.obj"), "out/bunny.quad.obj");
  EXPECT_EQ(batch_output_path("meshes/bunny.obj", "", ".png"), "meshes/bunny.png");
}

TEST(Batch, FailingFilesAreReportedAndOthersContinueInParallel) {
  std::vector<std::string> files;
  for (int i = 0; i < 12; ++i) files.push_back("file" + std::to_string(i));
  GlobalOptions global;
  global.jobs = 2;
  std::mutex m;
  std::set<std::thread::id> threads;
  std::ostringstream log;
  const auto results = process_files(
      files, global,
      [&](const std::string& in, ProgressSink&) {
        {
          std::lock_guard lock(m);
          threads.insert(std::this_thread::get_id());
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        const int i = std::stoi(in.substr(4));
        if (i == 3) throw InputError(in, 7, "bad token");
        if (i == 8) throw std::runtime_error("solver exploded");
        if (i == 10) throw TopologyError("not manifold", {"edge 1 2", "edge 3 4"});
        return nlohmann::json{{"index", i}, {"square", i * i}};
      },
      log);
  ASSERT_EQ(results.size(), files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    EXPECT_EQ(results[i].input, files[i]);  // input order, whatever the scheduling
    if (i == 3 || i == 8 || i == 10) continue;
    EXPECT_EQ(results[i].exit_code, kOk);
    EXPECT_EQ(results[i].result["square"], static_cast<int>(i * i));
  }
  EXPECT_EQ(results[3].exit_code, kBadInput);
  EXPECT_EQ(results[3].error, "file3:7: bad token");
  EXPECT_EQ(results[8].exit_code, kInternal);
  EXPECT_EQ(results[10].exit_code, kBadInput);
  EXPECT_NE(results[10].error.find("edge 3 4"), std::string::npos);
  EXPECT_EQ(batch_exit_code(results), kBadInput);
  EXPECT_GE(threads.size(), 2u);  // ran on two workers at once
  EXPECT_NE(log.str().find("[12/12]"), std::string::npos);
  EXPECT_NE(log.str().find("error: solver exploded"), std::string::npos);

  std::ostringstream table;
  print_summary(results, {"square"}, global, table);
  EXPECT_NE(table.str().find("9 of 12 files succeeded, 3 failed"), std::string::npos);
  EXPECT_NE(table.str().find("121"), std::string::npos);  // file11's square in the table

  std::ostringstream json_out;
  global.json = true;
  print_summary(results, {"square"}, global, json_out);
  const auto j = nlohmann::json::parse(json_out.str());
  EXPECT_EQ(j["succeeded"], 9);
  EXPECT_EQ(j["failed"], 3);
  EXPECT_EQ(j["files"][8]["error"], "solver exploded");
  EXPECT_EQ(j["files"][5]["result"]["index"], 5);
}

TEST(Batch, InterruptedBatchSkipsFilesNotStarted) {
  GlobalOptions global;
  global.jobs = 1;
  std::ostringstream log;
  clear_interrupt();
  const auto results = process_files(
      {"a", "b", "c"}, global,
      [](const std::string& in, ProgressSink& p) {
        if (in == "a") request_interrupt();
        EXPECT_EQ(p.cancelled(), true);
        return nlohmann::json{{"ok", true}};
      },
      log);
  clear_interrupt();
  EXPECT_EQ(results[0].exit_code, kOk);  // the running file finishes with its best result
  EXPECT_EQ(results[1].exit_code, kInternal);
  EXPECT_EQ(results[2].error, "not started: interrupted");
}

TEST(Outputs, JsonIsWrittenAtomicallyAndFailureLeavesNoFile) {
  const fs::path dir = fresh_dir("json");
  const std::string path = (dir / "r.json").string();
  write_json_atomically(path, {{"E_D", 1.25}});
  std::ifstream in(path);
  EXPECT_EQ(nlohmann::json::parse(in)["E_D"], 1.25);
  EXPECT_THROW(write_json_atomically((dir / "no/such/dir/r.json").string(), {{"a", 1}}), InputError);
  std::size_t count = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++count;
  EXPECT_EQ(count, 1u);  // no temporary left behind
  fs::remove_all(dir);
}

// METIS traps SIGTERM with its own handler while it orders: a SIGTERM sent then used to end the ordering, not the
// process. The watcher thread of run_watching_signals takes it instead. The child orders new grids for up to 10 s
// (almost all of its time in METIS) while writing a file; SIGTERM after 300 ms must end it with 128 + SIGTERM and no
// file. Without the CHOLMOD build there is no METIS and the test checks the same exit on the plain job.
TEST(Cancellation, SigtermDuringAMetisOrderingEndsTheProcess) {
  const fs::path dir = fresh_dir("metis_signal");
  const std::string target = (dir / "out.txt").string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    clear_interrupt();
    install_interrupt_handler();
    ::_exit(run_watching_signals([&] {
      write_file_atomically(target, [](std::ostream& out) {
        out << "x" << std::flush;
        const auto start = std::chrono::steady_clock::now();
        for (int m = 200; std::chrono::steady_clock::now() - start < std::chrono::seconds(10); ++m)
          if (nested_dissection_ordering(testing::grid_matrix<Complex>(m), 1).empty())
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
      });
      return 0;
    }));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM) << "the ordering swallowed SIGTERM";
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadcover::cli

namespace quadcover::cli {
namespace {

TEST(Cancellation, SigintSetsTheFlagAndTheNextOneIsFatal) {
  clear_interrupt();
  install_interrupt_handler();
  ASSERT_EQ(std::raise(SIGINT), 0);  // the handler runs synchronously in this thread
  EXPECT_TRUE(interrupted());
  std::ostringstream out;
  ProgressStyle style;
  TerminalProgress p(out, style);
  EXPECT_TRUE(p.cancelled());
  clear_interrupt();
  std::signal(SIGINT, SIG_DFL);
}

// In a child process: starts an atomic write of `target` and, half-way through, sends itself `signals` (in order).
// Returns the child's wait status.
int write_interrupted_by(const std::string& target, std::vector<int> signals) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    clear_interrupt();
    install_interrupt_handler();
    write_file_atomically(target, [&](std::ostream& out) {
      out << std::string(1 << 16, 'x') << std::flush;  // the temporary exists and holds data
      for (int sig : signals) std::raise(sig);
      out << "end";
    });
    ::_exit(0);  // not reached when a signal ends the process
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

// Issue 18 item 3: SIGTERM, SIGHUP, SIGQUIT, SIGPIPE and a second Ctrl-C during a write exit with 128 + signal and
// leave neither the output nor its temporary; a crash signal (SIGABRT) also leaves no temporary.
TEST(Cancellation, TerminatingSignalsRemoveTemporaryFilesAndExitWith128PlusSignal) {
  const fs::path dir = fresh_dir("signals");
  for (const int sig : {SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGUSR1}) {
    const int status = write_interrupted_by((dir / "out.txt").string(), {sig});
    ASSERT_TRUE(WIFEXITED(status)) << "signal " << sig << " killed the process without cleaning up";
    EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
    EXPECT_TRUE(fs::is_empty(dir)) << "signal " << sig << " left a file";
  }
  const int twice = write_interrupted_by((dir / "out.txt").string(), {SIGINT, SIGINT});
  ASSERT_TRUE(WIFEXITED(twice));
  EXPECT_EQ(WEXITSTATUS(twice), 128 + SIGINT);
  EXPECT_TRUE(fs::is_empty(dir));
  // One Ctrl-C only asks the work to stop: the write itself completes.
  const int once = write_interrupted_by((dir / "out.txt").string(), {SIGINT});
  ASSERT_TRUE(WIFEXITED(once));
  EXPECT_EQ(WEXITSTATUS(once), 0);
  EXPECT_TRUE(fs::exists(dir / "out.txt"));
  fs::remove(dir / "out.txt");
#if !defined(__SANITIZE_ADDRESS__)
  const int crash = write_interrupted_by((dir / "out.txt").string(), {SIGABRT});
  EXPECT_TRUE(WIFSIGNALED(crash) && WTERMSIG(crash) == SIGABRT) << "a crash keeps its signal";
  EXPECT_TRUE(fs::is_empty(dir));
#endif
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadcover::cli
