#pragma once
// Running the built CLI from tests: the binary is QUADCOVER_CLI (defined for every test executable). Header-only so
// that the macro of the including test applies.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>

namespace quadcover::testing {

struct CliRun {
  int code;         ///< exit status; -1 if killed by a signal or by the timeout
  std::string out;  ///< standard output
  std::string err;  ///< standard error (when a stderr file was given)
};

/// The whole content of a file (binary).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// An empty folder temp/quadcover_PREFIX_NAME_PID (removed first if it exists), for a test's files.
inline std::filesystem::path fresh_dir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("quadcover_" + prefix + "_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// A test with its own empty folder fresh_dir(PREFIX, "files"), removed afterwards; path(NAME) is a file in it.
class FolderTest : public ::testing::Test {
 protected:
  explicit FolderTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override { dir = fresh_dir(prefix_, "files"); }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::string path(const std::string& name) const { return (dir / name).string(); }
  std::filesystem::path dir;

 private:
  std::string prefix_;
};

/// CLI options that leave out Algorithm 6.1 and the stages that repair the map's validity (cone merges and moves
/// with their remake, fold refinement, validity retries), for tests whose subject does not depend on them (file
/// formats, options, the field stage): on camelhead_boundary they cost most of a run.
inline constexpr const char* kWithoutRepairs =
    " --optimize none --merge-cones false --move-cones false --refine-folds 0 --retries 0";

/// Runs `quadcover ARGS` and captures stdout. stderr goes to `stderr_file` (read back into CliRun::err) or is
/// discarded. timeout_seconds > 0 kills a hanging run (reported as code -1) instead of blocking the suite.
inline CliRun run_cli(const std::string& args, const std::string& stderr_file = "", int timeout_seconds = 0) {
  std::string cmd = std::string(QUADCOVER_CLI) + " " + args + " 2>" + (stderr_file.empty() ? "/dev/null" : stderr_file);
  if (timeout_seconds > 0) cmd = "timeout -s KILL " + std::to_string(timeout_seconds) + " " + cmd;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return {-1, "", "popen failed"};
  std::string out;
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (timeout_seconds > 0 && (code == 124 || code == 137)) code = -1;
  return {code, out, stderr_file.empty() ? std::string() : slurp(stderr_file)};
}

/// Runs `quadcover ARGS --report JSON`, expects exit 0 (the failure names the command) and returns the report.
inline nlohmann::json run_cli_report(const std::string& args, const std::string& json) {
  const std::string full = args + " --report " + json;
  EXPECT_EQ(run_cli(full).code, 0) << full;
  return nlohmann::json::parse(slurp(json));
}

}  // namespace quadcover::testing
