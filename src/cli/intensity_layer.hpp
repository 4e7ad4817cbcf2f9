// The intensity layer of a run (issue 17, item 3; docs/layers.md, "intensity.tif"): the classes
// of the chosen guideline (--intensity, [outputs] intensity) from the run's layers, written with
// its style, counted for run.json and the terminal.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/core/grid.hpp"
#include "talus/gis/layer_writer.hpp"
#include "talus/hazard/intensity_classes.hpp"

namespace talus::cli {

// The built-in guideline every run uses unless told otherwise.
inline constexpr const char* kDefaultIntensity = "foen-2016";

// A run's layers with their file names, descriptions and units.
using HazardLayers = std::vector<std::pair<const Grid<float>*, gis::LayerDescription>>;

// The scheme of `choice` ("none": no intensity layer) for process "rockfall" or "mudflow",
// checked before any work: every layer its thresholds name must be among `layers` (names only
// are read, so the grids may be empty).
std::optional<IntensityScheme> chosen_intensity(const std::string& choice, const std::string& process,
                                                const HazardLayers& layers);

// Classifies, adds intensity.tif to the set and returns the run.json entry: the guideline, and per
// class its cells and area (km2), and with a `passages` layer (rock fall) its cells passed by
// fewer than kQuantilePassages rocks.
nlohmann::json add_intensity_layer(gis::LayerWriter& writer, const IntensityScheme& scheme,
                                   const std::map<std::string, const Grid<float>*>& layers);

// Writes a run's layers and, when a guideline is chosen, their intensity classes; returns the
// intensity's run.json entry (null without a guideline).
nlohmann::json write_layers_with_intensity(gis::LayerWriter& writer, const HazardLayers& layers,
                                           const std::optional<IntensityScheme>& intensity);

// "Intensity (foen-2016): strong 12 cells (0.000 km2), ...", for the terminal.
std::string intensity_summary(const nlohmann::json& entry);

// Passages a cell needs for its 95th percentile of energy to lie inside its sample rather than
// at its largest value: 1 / (1 - 0.95) (docs/hazard-statistics.md, "Convergence").
inline constexpr int kQuantilePassages = 20;

// Share of a class's cells under kQuantilePassages above which its area is a problem line.
inline constexpr double kThinClassShare = 0.10;

// One problem line per intensity class (rock fall) more than kThinClassShare of whose cells
// were passed by fewer than kQuantilePassages rocks ("intensity: ...").
std::vector<std::string> intensity_problems(const nlohmann::json& entry);

}  // namespace talus::cli
