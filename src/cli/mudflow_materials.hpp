// Mud-flow material presets (docs/mudflow.md, "Materials"): named sets of scenario parameters
// (rheology, friction, turbulence, density) from the debris-flow and avalanche literature, that a
// user names instead of numbers. They live in one TOML file, src/cli/mudflow_materials.toml,
// built into the program, with each preset's sources beside it.
#pragma once

#include <map>
#include <string>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "parameter_table.hpp"

namespace talus::cli {

class MudflowMaterials {
 public:
  // The presets built into the program.
  static const MudflowMaterials& built_in();
  explicit MudflowMaterials(const std::string& toml_text);

  // The preset a run uses when neither --material nor [mud] material names one.
  const std::string& default_name() const { return default_name_; }
  bool contains(const std::string& name) const { return presets_.count(name) > 0; }
  // "debris-flow, granular, ...": every name, for messages and help.
  std::string name_list() const;
  // Sets the preset's parameters in `table` as Origin::material: below the scenario file and the
  // command line. The name must be one of the presets.
  void apply(const std::string& name, ParameterTable& table) const;
  // {name: {description, parameters: {section: {key: value}}}}, for `talus params`.
  nlohmann::json describe() const;

 private:
  struct Preset {
    std::string description;
    toml::table parameters;  // [section] key = value, as in a scenario file
  };
  std::string default_name_;
  std::map<std::string, Preset> presets_;
};

}  // namespace talus::cli
