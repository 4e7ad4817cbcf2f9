// The parameters of `talus mudflow` (docs/architecture.md section 5, issue 18, item 1): its options, the
// scenario file's keys with their units, meanings and ranges, the material presets under them, and
// the checks a run makes before it reads any input. Apart from the simulation so that the scenario
// fuzz target builds without it (docs/fuzzing.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "intensity_layer.hpp"
#include "mudflow_materials.hpp"
#include "parameter_table.hpp"
#include "run_choices.hpp"
#include "tile_plan.hpp"
#include "talus/gis/particle_snapshot_writer.hpp"
#include "talus/gis/scene.hpp"
#include "talus/mudflow/mudflow_simulation.hpp"

namespace talus::cli {

struct MudflowOptions {
  gis::SceneInputs inputs;
  std::filesystem::path out;
  std::filesystem::path scenario;
  std::string material = MudflowMaterials::built_in().default_name();  // --material, [mud] material
  std::string rheology = to_string(RheologyParameters{}.rheology);
  std::string adaptive = "on";  // --adaptive on|off, into settings.adaptive
  std::string release_thickness = "auto";  // [mud] release_thickness, parsed into the choice below
  // Resolved into settings.release_thickness by the job once the release is read.
  ReleaseThicknessChoice release_thickness_choice = ReleaseThicknessChoice::automatic;
  std::string pressure = to_string(PressureColumn::normal);             // into settings.pressure
  double release_depth = 0;            // m: --depth, [mud] release_depth; 0: the release file's depths
  std::string depth_field = "depth";   // --depth-field, [mud] depth_field
  std::string snapshot_start = gis::kDefaultSnapshotStart;  // --start-time, [outputs] snapshot_start
  std::int64_t snapshot_start_seconds = 0;                  // s after 1970-01-01, from snapshot_start
  std::string project = "on";  // --project on|off, [outputs] project
  std::string intensity = kDefaultIntensity;                // --intensity, [outputs] intensity
  MudflowSettings settings;
  // [tiles], --memory, --halo (docs/study.md, "Tiles"): a region whose ground does not fit runs the
  // flow on a window around its release; debris flows run further than rocks, so the halo is wider.
  TileChoice tiles{0, 5000, 0};
  std::vector<std::string> command_line;
};

// Every MudflowSettings field (mudflow_simulation.hpp, rheology.hpp) of `o` as a scenario key, with
// its unit, meaning and range.
ParameterTable mudflow_parameter_table(MudflowOptions& o);

// The scenario file, the material preset and the flags resolved into `o` (`adaptive_given`:
// --adaptive was given), every parameter checked: what a run does before it reads any input;
// throws InputError naming the flag or scenario key.
RunChoices resolve_mudflow_parameters(MudflowOptions& o, ParameterTable& table, bool adaptive_given);

// What `talus mudflow --scenario FILE` resolves and checks before any work, with no flag given;
// throws InputError where such a run would refuse the file. The scenario fuzz target calls it.
void check_mudflow_scenario(const std::filesystem::path& scenario);

// Every mud-flow parameter with its section, unit, meaning, default (the default material's) and
// range (`talus params`).
nlohmann::json mudflow_parameters();
// The mud-flow material presets with their descriptions and parameters (`talus params`).
nlohmann::json mudflow_materials();

}  // namespace talus::cli
