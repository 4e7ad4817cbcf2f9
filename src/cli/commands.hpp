// The `talus` subcommands (docs/architecture.md section 3). Each adds itself to the parser and sets the
// action that main runs once parsing succeeded.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "process_ranks.hpp"

namespace talus::cli {

using Action = std::function<int()>;

void add_info_command(CLI::App& app, Action& action);
// rockfall and study split their work among the MPI ranks (process_ranks.hpp); the others
// refuse to run in more than one.
void add_rockfall_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line,
                          const ProcessRanks& ranks);
void add_params_command(CLI::App& app, Action& action);
void add_calibrate_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line);
void add_mudflow_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line);
void add_study_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line,
                       const ProcessRanks& ranks);

}  // namespace talus::cli
