// The parameters of `talus rockfall` (docs/architecture.md section 5, issue 18, item 1): its options, the
// scenario file's keys with their units, meanings and ranges, and the checks a run makes before it
// reads any input. Apart from the simulation so that the scenario fuzz target builds without it
// (docs/fuzzing.md).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "intensity_layer.hpp"
#include "parameter_table.hpp"
#include "run_choices.hpp"
#include "tile_plan.hpp"
#include "talus/gis/scene.hpp"
#include "talus/rockfall/fast_bounce.hpp"
#include "talus/rockfall/full_model.hpp"
#include "talus/rockfall/monte_carlo.hpp"

namespace talus::cli {

struct RockfallOptions {
  gis::SceneInputs inputs;
  std::filesystem::path out;
  std::filesystem::path scenario;
  std::string mode = "fast";
  std::string block_shape = "sphere";
  std::string block_size = "1";
  CountOrAuto runs{true, 0};   // into settings.runs_per_source and settings.auto_runs
  std::string runs_flag;       // --runs as given
  std::string project = "on";  // --project on|off, [outputs] project
  std::string intensity = kDefaultIntensity;  // --intensity, [outputs] intensity
  RockfallSettings settings;
  FastBounceParameters fast;
  FullModelParameters full;
  double fracture_strength = FullModelParameters{}.fracture_strength / 1000.0;  // kN, into full.fracture_strength (N)
  TileChoice tiles;            // [tiles], --memory, --halo, --tile-size (tile_plan.hpp)
  double failure_share = 1.0;  // %: more failed trajectories than this fail the run (exit code 3)
  // A study's resume within the scenario (unit_parts.hpp): the folder its units of work are
  // committed to, and what their results depend on; empty: not committed.
  std::filesystem::path unit_parts;
  std::string unit_key;
  std::vector<std::string> command_line;
};

// Every rock-fall parameter of `o` as a scenario key, with its unit, meaning and range.
ParameterTable rockfall_parameter_table(RockfallOptions& o);

// The scenario file and the flags resolved into `o`, every parameter checked: what a run does
// before it reads any input; throws InputError naming the flag or scenario key.
RunChoices resolve_rockfall_parameters(RockfallOptions& o, ParameterTable& table);

// What `talus rockfall --scenario FILE` resolves and checks before any work, with no flag given;
// throws InputError where such a run would refuse the file. The scenario fuzz target calls it.
void check_rockfall_scenario(const std::filesystem::path& scenario);

// Every rock-fall parameter with its section, unit, meaning, default and range (`talus params`).
nlohmann::json rockfall_parameters();

}  // namespace talus::cli
