// Rock-fall sources a study finds from the slope (issue 19, item 1; docs/study.md, "Sources from
// the slope"): for each scenario with release = "auto", the cells steeper than its threshold (the
// DEM's own, by Loye et al. 2009, or the scenario's source_slope) and of its lithology classes,
// written as DIR/sources/NAME.tif, the scenario's release raster.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "study_file.hpp"
#include "talus/core/grid.hpp"
#include "talus/hazard/rockfall_source_detection.hpp"

namespace talus::cli {

struct DetectedSources {
  Grid<float> mask;                  // 1 source, 0 not
  std::array<SlopeUnit, 4> units;    // the slope angle distribution's decomposition
  double threshold_deg = 0;          // the slope from which a cell is a source
  bool threshold_from_dem = true;    // false: the scenario's source_slope
  std::size_t cells = 0;
};

// The study's slope angles, their decomposition and the lithology, computed once for all the
// scenarios that find their sources.
struct SlopeAnalysis {
  Grid<float> slopes;               // degrees (Horn)
  std::array<SlopeUnit, 4> units;   // the slope angle distribution's decomposition
  Grid<int> lithology;              // class per cell, as the runs read it
};
SlopeAnalysis analyse_slopes(const Study& study);

// The sources of `s` (detect_sources) from the study's slopes; InputError naming the scenario when
// none are found or the distribution has no cliff unit and no source_slope is given.
DetectedSources detect_sources(const SlopeAnalysis& analysis, const StudyScenario& s);

// The release raster a scenario with detected sources runs from.
std::filesystem::path detected_sources_path(const std::filesystem::path& out, const StudyScenario& s);

// Writes DIR/sources/ (NAME.tif per scenario with detected sources, styled, and run.json) and
// returns study.json's "sources" entry; `detected` follows the study's scenarios (none for those
// with a release file).
nlohmann::ordered_json write_detected_sources(const Study& study, const std::filesystem::path& out,
                                              const std::vector<std::string>& command_line,
                                              const std::vector<std::optional<DetectedSources>>& detected);

}  // namespace talus::cli
