// The `talus` subcommands (DESIGN.md section 3). Each adds itself to the parser and sets the
// action that main runs once parsing succeeded.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

namespace talus::cli {

using Action = std::function<int()>;

void add_info_command(CLI::App& app, Action& action);
void add_rockfall_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line);
void add_params_command(CLI::App& app, Action& action);
void add_calibrate_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line);
void add_mudflow_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line);

// The parameters of `talus rockfall --scenario FILE` and `talus mudflow --scenario FILE` read
// and checked as a run does before it reads any input (its scenario file, material preset,
// intensity guideline and every range), with no flag given; throws InputError where the run
// would refuse them. The scenario fuzz target calls these (docs/fuzzing.md).
void check_rockfall_scenario(const std::filesystem::path& scenario);
void check_mudflow_scenario(const std::filesystem::path& scenario);

// Every rock-fall parameter with its section, unit, meaning and default.
nlohmann::json rockfall_parameters();
// Every mud-flow parameter with its section, unit, meaning and default (the default material's).
nlohmann::json mudflow_parameters();
// The mud-flow material presets with their descriptions and parameters.
nlohmann::json mudflow_materials();

}  // namespace talus::cli
