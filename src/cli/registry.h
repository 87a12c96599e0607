#pragma once
// Subcommands register themselves here (one source file per command in src/cli/), so adding a command never
// touches main.cpp. `order` sorts them in --help.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "cli/commands.h"

namespace quadcover::cli {

/// Adds the options and the callback of the subcommand `cmd` (created by main with the entry's name and description).
using RegisterFn = std::function<void(CLI::App* cmd, GlobalOptions& global, int& exit_code)>;

struct CommandEntry {
  int order;
  std::string name;
  RegisterFn fn;
  std::string description;  ///< the subcommand's line in --help
};

inline std::vector<CommandEntry>& command_registry() {  ///< \pre none
  static std::vector<CommandEntry> registry;
  return registry;
}

/// Place `static const CommandRegistrar reg{10, "info", register_info, "DESCRIPTION"};` in the command's source file.
struct CommandRegistrar {
  CommandRegistrar(int order, std::string name, RegisterFn fn, std::string description) {  ///< \pre none
    command_registry().push_back({order, std::move(name), std::move(fn), std::move(description)});
  }
};

}  // namespace quadcover::cli
