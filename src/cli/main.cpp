// quadcover command-line tool: dispatches to the subcommands and maps errors to exit codes.
#include <iostream>

#include <algorithm>

#include "cli/registry.h"
#include "common/errors.h"

int main(int argc, char** argv) {
  using namespace quadcover;
  CLI::App app{"quadcover: seamless quad-aligned parameterization and quad remeshing (QuadCover, Kälberer)"};
  app.set_version_flag("--version", std::string("quadcover ") + QUADCOVER_VERSION);
  app.require_subcommand(1);
  cli::GlobalOptions global;
  int exit_code = cli::kOk;
  auto& commands = cli::command_registry();
  std::sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& c : commands) c.fn(app, global, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : cli::kBadInput;
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return cli::kBadInput;
  } catch (const TopologyError& e) {
    std::cerr << "error: " << e.what() << "\n";
    for (const auto& p : e.problems()) std::cerr << "  " << p << "\n";
    return cli::kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return cli::kInternal;
  }
  return exit_code;
}
