// The `talus` subcommands (DESIGN.md section 3). Each adds itself to the parser and sets the
// action that main runs once parsing succeeded.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace talus::cli {

using Action = std::function<int()>;

void add_info_command(CLI::App& app, Action& action);

}  // namespace talus::cli
