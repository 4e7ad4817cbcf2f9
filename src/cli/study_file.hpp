// The study file of `talus study` (issue 19, item 1; docs/study.md): the region's inputs, shared
// by every scenario, and the rock-fall and mud-flow scenarios, each with its release, its return
// period and the parameters of its subcommand, by the same sections and keys as a scenario file
// (`talus params`).
#pragma once

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "talus/gis/hazard_zones_writer.hpp"
#include "talus/gis/scene.hpp"

namespace talus::cli {

enum class StudyProcess { rockfall, mudflow };
const char* to_string(StudyProcess process);

struct StudyScenario {
  StudyProcess process = StudyProcess::rockfall;
  std::string name;                   // its folder under scenarios/: letters, digits, '-', '_', '.'
  std::filesystem::path release;      // raster or vector layer, as --release; empty with detect_sources
  // Rock fall, release = "auto": sources from the slope (docs/study.md, "Sources from the slope"):
  // steeper than source_slope (degrees) or, without it, than the DEM's cliff threshold (Loye et al.
  // 2009), and of a lithology class in source_lithology (all classes when empty).
  bool detect_sources = false;
  std::optional<double> source_slope;
  std::set<int> source_lithology;
  std::filesystem::path erodible;     // mud flow only, as --erodible; empty: none
  std::filesystem::path scenario;     // a scenario file under the study's keys, as --scenario; empty: none
  double return_period_years = 0;     // from return_period (years) or annual_frequency (1/year)
  toml::table parameters;             // the subcommand's sections: [run], [rock], [mud], ...
  std::string where;                  // "F.toml (study): [[rockfall]] NAME", for messages
};

struct Study {
  std::filesystem::path file;
  // [hazard] rockfall_probability: "reach" (default), a rock fall's return period at a cell is the
  // scenario's over the cell's reach probability; "onset", the scenario's wherever a rock reaches.
  bool rockfall_reach = true;
  gis::ZoneGeneralisation zones;  // [hazard] minimum_zone_m2 and smooth_zones (docs/study.md, "Hazard zones")
  gis::SceneInputs inputs;  // dem, lithology, vegetation, materials, crs
  std::vector<StudyScenario> scenarios;  // in the file's order: rock falls, then mud flows
};

// Reads and checks the study file: known sections and keys, required ones present, names unique,
// a return period in (0, 1e6] years; paths relative to the file's folder. Throws InputError naming
// the file and the key. The scenarios' own parameters are checked by check_study_scenarios().
Study read_study(const std::filesystem::path& file);

}  // namespace talus::cli
