// `talus params`: every parameter of every model as JSON (DESIGN.md section 1: the QGIS
// provider and the docs are generated from it).
#include <iostream>

#include "commands.hpp"
#include "intensity_guidelines.hpp"

namespace talus::cli {

void add_params_command(CLI::App& app, Action& action) {
  CLI::App* cmd = app.add_subcommand("params", "Print every parameter (section, name, unit, meaning, default) as JSON");
  cmd->callback([&action] {
    action = [] {
      const nlohmann::json all = {{"rockfall", rockfall_parameters()},
                                  {"mudflow", mudflow_parameters()},
                                  {"mudflow_materials", mudflow_materials()},
                                  {"intensity_guidelines", built_in_intensity_guidelines()}};
      std::cout << all.dump(2) << '\n';
      return 0;
    };
  });
}

}  // namespace talus::cli
