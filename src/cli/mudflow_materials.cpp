// The mud-flow material presets of src/cli/mudflow_materials.toml (docs/mudflow.md, "Materials").
#include "mudflow_materials.hpp"

#include <sstream>
#include <stdexcept>
#include <string_view>

#include "mudflow_materials_text.hpp"

namespace talus::cli {

const MudflowMaterials& MudflowMaterials::built_in() {
  static const MudflowMaterials materials(kMudflowMaterialsToml);
  return materials;
}

// The file holds `default = "NAME"` and one table per preset: `description` and its parameters
// as dotted keys (mud.density = 2000). A malformed built-in file is a programming error.
MudflowMaterials::MudflowMaterials(const std::string& toml_text) {
  const toml::table file = toml::parse(std::string_view(toml_text), std::string_view("mudflow_materials.toml"));
  for (const auto& [key, node] : file) {
    const std::string name(key.str());
    if (name == "default") {
      default_name_ = node.value<std::string>().value_or("");
      continue;
    }
    const toml::table* preset = node.as_table();
    if (preset == nullptr) throw std::logic_error("mudflow_materials.toml: '" + name + "' is not a table");
    Preset entry;
    entry.description = (*preset)["description"].value<std::string>().value_or("");
    entry.parameters = *preset;
    entry.parameters.erase("description");
    presets_.emplace(name, std::move(entry));
  }
  if (!contains(default_name_)) throw std::logic_error("mudflow_materials.toml: no preset named by `default`");
}

std::string MudflowMaterials::name_list() const {
  std::string list;
  for (const auto& [name, preset] : presets_) list += (list.empty() ? "" : ", ") + name;
  return list;
}

void MudflowMaterials::apply(const std::string& name, ParameterTable& table) const {
  table.apply(presets_.at(name).parameters, ParameterTable::Origin::material, "material " + name);
}

nlohmann::json MudflowMaterials::describe() const {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, preset] : presets_) {
    std::ostringstream json;
    json << toml::json_formatter{preset.parameters};
    out[name] = {{"description", preset.description}, {"parameters", nlohmann::json::parse(json.str())}};
  }
  return out;
}

}  // namespace talus::cli
