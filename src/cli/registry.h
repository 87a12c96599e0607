#pragma once
// Subcommands register themselves here (one source file per command in src/cli/), so adding a command never
// touches main.cpp. `order` sorts them in --help.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "cli/commands.h"

namespace quadcover::cli {

using RegisterFn = std::function<void(CLI::App& app, GlobalOptions& global, int& exit_code)>;

struct CommandEntry {
  int order;
  std::string name;
  RegisterFn fn;
};

inline std::vector<CommandEntry>& command_registry() {
  static std::vector<CommandEntry> registry;
  return registry;
}

/// Place `static const CommandRegistrar reg{10, "info", register_info};` in the command's source file.
struct CommandRegistrar {
  CommandRegistrar(int order, std::string name, RegisterFn fn) {
    command_registry().push_back({order, std::move(name), std::move(fn)});
  }
};

}  // namespace quadcover::cli
