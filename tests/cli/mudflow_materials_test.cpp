// Mud-flow material presets (issue 20, item 3; docs/mudflow.md section 5, "Materials"): the
// default preset is the engine's default, docs/mudflow.md's table holds the program's presets,
// every preset runs, and a preset gives way to the scenario's keys and to the flags.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run_talus.hpp"
#include "talus/mudflow/mudflow_simulation.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

nlohmann::json talus_params() {
  const auto result = test::run_talus({"params"}, test::fresh_folder("mudflow_materials_params"));
  EXPECT_EQ(result.exit_code, 0) << result.err;
  return nlohmann::json::parse(result.out);
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

// A short run of the sample scene (5 m particles, 10 s of flow) with more arguments.
test::ProgramResult short_sample_run(const fs::path& out, const std::vector<std::string>& more) {
  const auto sample = test::source_dir() / "sample_dem";
  std::vector<std::string> arguments = {"mudflow", "--dem", (sample / "dem.tif").string(), "--release",
                                        (sample / "mudflow_release.gpkg").string(), "--out", out.string(),
                                        "--particle-size", "5", "--duration", "10", "--threads", "1"};
  arguments.insert(arguments.end(), more.begin(), more.end());
  return test::run_talus(arguments, out.parent_path());
}

TEST(MudflowMaterials, DefaultPresetIsTheEnginesDefault) {
  const nlohmann::json params = talus_params();
  std::string default_material;
  for (const auto& entry : params["mudflow"]) {
    if (entry["section"] == "mud" && entry["name"] == "material") default_material = entry["default"];
  }
  ASSERT_EQ(default_material, "debris-flow");
  const auto& preset = params["mudflow_materials"][default_material]["parameters"];
  const MudflowSettings engine;
  EXPECT_EQ(preset["mud"]["density"].get<double>(), engine.mud_density);
  EXPECT_EQ(preset["rheology"]["rheology"].get<std::string>(), to_string(engine.rheology.rheology));
  EXPECT_EQ(preset["rheology"]["friction"].get<double>(), engine.rheology.friction);
  EXPECT_EQ(preset["rheology"]["turbulence"].get<double>(), engine.rheology.turbulence);
  EXPECT_EQ(preset["rheology"]["yield_stress"].get<double>(), engine.rheology.yield_stress);
}

// The rows of docs/mudflow.md's materials table: | `name` ... | rheology | mu | xi | tau_y | density | source |.
std::map<std::string, std::vector<std::string>> documented_presets() {
  std::ifstream file(test::source_dir() / "docs" / "mudflow.md");
  std::map<std::string, std::vector<std::string>> rows;
  std::string line;
  bool in_table = false;
  while (std::getline(file, line)) {
    if (line.rfind("| preset | rheology |", 0) == 0) {
      in_table = true;
      continue;
    }
    if (!in_table || line.rfind("|---", 0) == 0) continue;
    if (line.rfind("| `", 0) != 0) break;
    std::vector<std::string> cells;
    std::stringstream cells_text(line.substr(1));
    std::string cell;
    while (std::getline(cells_text, cell, '|')) cells.push_back(cell);
    const std::size_t open = cells[0].find('`');
    const std::string name = cells[0].substr(open + 1, cells[0].find('`', open + 1) - open - 1);
    rows[name] = cells;
  }
  return rows;
}

TEST(MudflowMaterials, DocsTableHoldsTheProgramsPresets) {
  const nlohmann::json materials = talus_params()["mudflow_materials"];
  const auto rows = documented_presets();
  ASSERT_EQ(rows.size(), materials.size());
  for (const auto& [name, preset] : materials.items()) {
    ASSERT_TRUE(rows.count(name)) << name << " is not in docs/mudflow.md's table";
    const auto& cells = rows.at(name);
    ASSERT_GE(cells.size(), 7u) << name;
    const auto& p = preset["parameters"];
    EXPECT_NE(cells[1].find(p["rheology"]["rheology"].get<std::string>()), std::string::npos) << name;
    EXPECT_EQ(std::stod(cells[2]), p["rheology"]["friction"].get<double>()) << name;
    EXPECT_EQ(std::stod(cells[3]), p["rheology"]["turbulence"].get<double>()) << name;
    EXPECT_EQ(std::stod(cells[4]), p["rheology"]["yield_stress"].get<double>()) << name;
    EXPECT_EQ(std::stod(cells[5]), p["mud"]["density"].get<double>()) << name;
    EXPECT_GT(cells[6].size(), 20u) << name << ": no source";
  }
}

// Each preset runs and its values are the run's (none of them is overridden here).
TEST(MudflowMaterials, EveryPresetRunsWithItsValues) {
  const auto root = test::fresh_folder("mudflow_materials_each");
  const nlohmann::json materials = talus_params()["mudflow_materials"];
  for (const auto& [name, preset] : materials.items()) {
    const auto result = short_sample_run(root / name, {"--material", name});
    ASSERT_EQ(result.exit_code, 0) << name << ": " << result.err;
    EXPECT_NE(result.out.find("(" + name + ": voellmy"), std::string::npos) << result.out;
    const nlohmann::json parameters = read_json(root / name / "run.json")["parameters"];
    EXPECT_EQ(parameters["mud"]["material"], name);
    for (const auto& [section, keys] : preset["parameters"].items()) {
      for (const auto& [key, value] : keys.items()) EXPECT_EQ(parameters[section][key], value) << name << " " << key;
    }
  }
}

// Precedence (docs/mudflow.md, "Materials"): material < the scenario's own keys < flags, and the
// material named by --material wins over the scenario's [mud] material.
TEST(MudflowMaterials, PresetGivesWayToTheScenarioAndTheFlags) {
  const auto root = test::fresh_folder("mudflow_materials_precedence");
  std::ofstream(root / "snow.toml") << "[mud]\nmaterial = \"snow-avalanche\"\n[rheology]\nturbulence = 3000\n";
  const std::string scenario = (root / "snow.toml").string();

  auto result = short_sample_run(root / "scenario", {"--scenario", scenario, "--rheology", "coulomb"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  nlohmann::json parameters = read_json(root / "scenario" / "run.json")["parameters"];
  EXPECT_EQ(parameters["mud"]["material"], "snow-avalanche");
  EXPECT_EQ(parameters["mud"]["density"], 200.0);           // the material's
  EXPECT_EQ(parameters["rheology"]["friction"], 0.155);     // the material's
  EXPECT_EQ(parameters["rheology"]["turbulence"], 3000.0);  // the scenario's over the material's
  EXPECT_EQ(parameters["rheology"]["rheology"], "coulomb");  // the flag's over the material's

  result = short_sample_run(root / "flag", {"--scenario", scenario, "--material", "mud-flow"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  parameters = read_json(root / "flag" / "run.json")["parameters"];
  EXPECT_EQ(parameters["mud"]["material"], "mud-flow");     // the flag's over the scenario's
  EXPECT_EQ(parameters["mud"]["density"], 1800.0);
  EXPECT_EQ(parameters["rheology"]["friction"], 0.05);
  EXPECT_EQ(parameters["rheology"]["turbulence"], 3000.0);  // still the scenario's
}

}  // namespace
}  // namespace talus
