// quadcover command-line tool: dispatches to the subcommands and maps errors to exit codes.
#include <algorithm>
#include <iostream>

#include "cli/common.h"
#include "cli/huge_pages.h"
#include "cli/registry.h"

namespace {

// Parses the command line and runs the chosen subcommand; returns the exit code.
int run_command_line(int argc, char** argv) {
  using namespace quadcover;
  CLI::App app{"quadcover: seamless quad-aligned parameterization and quad remeshing (QuadCover, Kälberer)"};
  app.set_version_flag("--version", std::string("quadcover ") + QUADCOVER_VERSION);
  app.require_subcommand(1);
  cli::GlobalOptions global;
  int exit_code = cli::kOk;
  auto& commands = cli::command_registry();
  std::sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& c : commands) c.fn(app.add_subcommand(c.name, c.description), global, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : cli::kBadInput;
  } catch (...) {
    std::string message;
    const int code = cli::describe_current_exception(message);
    std::cerr << "error: " << message << "\n";
    return code;
  }
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace quadcover;
  cli::restart_with_huge_pages(argv);
  cli::use_one_heap_arena();
  cli::run_start_time();  // --time-limit counts from here
  cli::install_interrupt_handler();
  return cli::run_watching_signals([argc, argv] { return run_command_line(argc, argv); });
}
