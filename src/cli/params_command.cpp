// `talus params`: every parameter of every model as JSON (docs/architecture.md section 5: the QGIS
// provider builds its dialogs from it).
#include <iostream>

#include "commands.hpp"
#include "intensity_guidelines.hpp"
#include "mudflow_parameters.hpp"
#include "rockfall_parameters.hpp"
#include "talus/gis/materials_file.hpp"

namespace talus::cli {
namespace {

// The numbers of a materials file's classes with their units and ranges (docs/materials.md).
nlohmann::json materials_parameters() {
  nlohmann::json out = nlohmann::json::array();
  for (const gis::MaterialsField& f : gis::materials_fields()) {
    out.push_back({{"section", f.kind},
                   {"name", f.key},
                   {"unit", f.unit},
                   {"description", f.meaning},
                   {"range", {{"min", f.min}, {"max", f.max}, {"min_exclusive", false}, {"max_exclusive", false}}}});
  }
  return out;
}

}  // namespace

void add_params_command(CLI::App& app, Action& action) {
  CLI::App* cmd = app.add_subcommand("params", "Print every parameter (section, name, unit, meaning, default) as JSON");
  cmd->callback([&action] {
    action = [] {
      const nlohmann::json all = {{"rockfall", rockfall_parameters()},
                                  {"mudflow", mudflow_parameters()},
                                  {"mudflow_materials", mudflow_materials()},
                                  {"materials", materials_parameters()},
                                  {"intensity_guidelines", built_in_intensity_guidelines()}};
      std::cout << all.dump(2) << '\n';
      return 0;
    };
  });
}

}  // namespace talus::cli
