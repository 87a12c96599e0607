// The --report JSON of `param` and `remesh` carries the memory section (pipeline/job_report.h): a peak per timed
// stage, the CLI's reading first and writing last, and whether malloc asked for transparent huge pages
// (cli/huge_pages.h).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/report_memory.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

namespace fs = std::filesystem;

TEST(ReportMemoryCli, ParamAndRemeshReportsHaveAPeakPerTimedStage) {
  const fs::path dir = testing::fresh_dir("report_memory_cli", "stages");
  const std::string input = testing::data_path("bunny_3k");
  for (const std::string command : {"param", "remesh"}) {
    const std::string out = (dir / (command + ".obj")).string(), report = (dir / (command + ".json")).string();
    const testing::CliRun run =
        testing::run_cli(command + " " + input + " -o " + out + " --report " + report + " -q", "", 300);
    ASSERT_EQ(run.code, 0) << command;
    const nlohmann::json r = nlohmann::json::parse(testing::slurp(report));
    testing::expect_memory_matches_seconds(r);
    const nlohmann::json& stages = r["memory"]["stages"];
    ASSERT_GE(stages.size(), 4u) << command;
    EXPECT_EQ(stages.front()["stage"], "read") << command;
    EXPECT_EQ(stages.back()["stage"], "write") << command;
    EXPECT_GE(testing::memory_stage_index(r, "field"), 1) << command;
    EXPECT_EQ(testing::memory_stage_index(r, "extract") >= 0, command == "remesh");
  }
  fs::remove_all(dir);
}

// The stages that make the map again when it is not valid (the merges of close cones, the cone separation) have a
// peak too: mech_holes_shark at 6500 vertices runs both (without retries: the full optimization's attempt is valid).
TEST(ReportMemoryCli, TheStagesThatRemakeAnInvalidMapHaveAPeakToo) {
  const fs::path dir = testing::fresh_dir("report_memory_cli", "remakes");
  const std::string out = (dir / "out.obj").string(), report = (dir / "out.json").string();
  const testing::CliRun run =
      testing::run_cli("remesh " + testing::data_path("mech_holes_shark") + " --vertices 6500 --retries 0 -o " + out +
                           " --report " + report + " -q",
                       "", 300);
  ASSERT_EQ(run.code, 0) << run.err;
  const nlohmann::json r = nlohmann::json::parse(testing::slurp(report));
  ASSERT_TRUE(r["seconds"].contains("cone_separation") && r["seconds"].contains("close_cone_merging"))
      << "this mesh no longer needs them: choose another";
  testing::expect_memory_matches_seconds(r);
  EXPECT_GT(testing::memory_stage_index(r, "cone_separation"), testing::memory_stage_index(r, "close_cone_merging"));
  fs::remove_all(dir);
}

constexpr bool kGlibcMalloc =
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    false;  // the sanitizer's allocator
#else
    true;
#endif

/// Whether the CLI built like this test restarts itself with huge pages on this machine (cli/huge_pages.h).
bool cli_restarts_with_huge_pages() {
  if (!kGlibcMalloc) return false;
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(in, modes);
  return modes.find("[madvise]") != std::string::npos;
}

TEST(ReportMemoryCli, HugePagesUnlessTheUserSetTheTunablesOrSaidNo) {
  const fs::path dir = testing::fresh_dir("report_memory_cli", "huge_pages");
  const std::string args = std::string(" ") + QUADCOVER_CLI + " param " + testing::data_path("bunny_3k") +
                           testing::kWithoutRepairs + " -q -o " + (dir / "map.obj").string() + " --report ";
  auto huge_pages = [&](const std::string& env, const std::string& name) {
    const std::string report = (dir / (name + ".json")).string();
    EXPECT_EQ(std::system(("env -u GLIBC_TUNABLES -u QUADCOVER_NO_HUGE_PAGES " + env + args + report).c_str()), 0);
    fs::rename(dir / "map.obj", dir / (name + ".obj"));
    return nlohmann::json::parse(testing::slurp(report))["memory"]["huge_pages"].get<bool>();
  };
  EXPECT_EQ(huge_pages("", "default"), cli_restarts_with_huge_pages());
  EXPECT_FALSE(huge_pages("QUADCOVER_NO_HUGE_PAGES=1", "said_no"));
  EXPECT_FALSE(huge_pages("GLIBC_TUNABLES=glibc.malloc.check=0", "own_tunables"));
  EXPECT_EQ(huge_pages("GLIBC_TUNABLES=glibc.malloc.hugetlb=1", "own_huge_pages"), kGlibcMalloc);
  EXPECT_EQ(testing::slurp(dir / "default.obj"), testing::slurp(dir / "said_no.obj"));  // the same map either way
  fs::remove_all(dir);
}

/// The text of /proc/PID/FILE ("" if unreadable), NULs as spaces.
std::string proc_text(pid_t pid, const char* file) {
  std::string text = testing::slurp("/proc/" + std::to_string(pid) + "/" + file);
  std::replace(text.begin(), text.end(), '\0', ' ');
  return text;
}

/// Starts `quadcover info -` (which waits for the mesh on stdin) with OPENBLAS_NUM_THREADS as given (nullptr: unset),
/// waits until it has restarted with huge pages, and returns its /proc environ and comm; then lets it exit.
std::pair<std::string, std::string> restarted_environment_and_name(const char* blas_threads) {
  int to_child[2];
  if (::pipe(to_child) != 0) return {};
  const pid_t pid = ::fork();
  if (pid < 0) return {};
  if (pid == 0) {
    ::dup2(to_child[0], 0);
    ::close(to_child[1]);
    ::unsetenv("GLIBC_TUNABLES");
    ::unsetenv("QUADCOVER_NO_HUGE_PAGES");
    if (blas_threads)
      ::setenv("OPENBLAS_NUM_THREADS", blas_threads, 1);
    else
      ::unsetenv("OPENBLAS_NUM_THREADS");
    ::execl(QUADCOVER_CLI, QUADCOVER_CLI, "info", "-", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(to_child[0]);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  std::string environment;
  while (environment.find("GLIBC_TUNABLES=glibc.malloc.hugetlb=1") == std::string::npos &&
         std::chrono::steady_clock::now() < give_up) {
    ::usleep(10'000);
    environment = " " + proc_text(pid, "environ");  // every variable between spaces
  }
  const std::string name = proc_text(pid, "comm");
  ::close(to_child[1]);  // an empty mesh: info exits with an error
  int status = 0;
  EXPECT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status)) << status;
  return {environment, name};
}

TEST(ReportMemoryCli, TheRestartedProcessKeepsItsNameAndPid) {
  if (!cli_restarts_with_huge_pages()) GTEST_SKIP() << "no restart here: glibc's malloc absent or huge pages off";
  const auto [environment, name] = restarted_environment_and_name(nullptr);
  EXPECT_NE(environment.find("GLIBC_TUNABLES=glibc.malloc.hugetlb=1"), std::string::npos);
  EXPECT_EQ(name, "quadcover\n");  // ps, top and pkill still know it
}

// The restart starts OpenBLAS without its thread pool (cli/huge_pages.h), unless the user chose a thread count.
TEST(ReportMemoryCli, TheRestartedProcessStartsBlasOnOneThreadUnlessTold) {
  if (!cli_restarts_with_huge_pages()) GTEST_SKIP() << "no restart here: glibc's malloc absent or huge pages off";
  EXPECT_NE(restarted_environment_and_name(nullptr).first.find(" OPENBLAS_NUM_THREADS=1 "), std::string::npos);
  const std::string told = restarted_environment_and_name("3").first;
  EXPECT_NE(told.find(" OPENBLAS_NUM_THREADS=3 "), std::string::npos);
  EXPECT_EQ(told.find("OPENBLAS_NUM_THREADS=1"), std::string::npos);
}

}  // namespace
}  // namespace quadcover
