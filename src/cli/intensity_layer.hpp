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
// class its cells and area (km2).
nlohmann::json add_intensity_layer(gis::LayerWriter& writer, const IntensityScheme& scheme,
                                   const std::map<std::string, const Grid<float>*>& layers);

// Writes a run's layers and, when a guideline is chosen, their intensity classes; returns the
// intensity's run.json entry (null without a guideline).
nlohmann::json write_layers_with_intensity(gis::LayerWriter& writer, const HazardLayers& layers,
                                           const std::optional<IntensityScheme>& intensity);

// "Intensity (foen-2016): strong 12 cells (0.000 km2), ...", for the terminal.
std::string intensity_summary(const nlohmann::json& entry);

}  // namespace talus::cli
