// intensity.tif of a run (intensity_layer.hpp).
#include "intensity_layer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "intensity_guidelines.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/intensity_style.hpp"

namespace talus::cli {

std::optional<IntensityScheme> chosen_intensity(const std::string& choice, const std::string& process,
                                                const HazardLayers& layers) {
  if (choice == "none") return std::nullopt;
  std::vector<std::string> layer_names;
  for (const auto& entry : layers) layer_names.push_back(entry.second.name);
  IntensityScheme scheme = intensity_scheme(choice, process);
  for (const IntensityClass& c : scheme.classes) {
    for (const auto& alternative : c.when) {
      for (const IntensityThreshold& threshold : alternative) {
        for (const std::string& layer : threshold.layers) {
          if (std::ranges::find(layer_names, layer) != layer_names.end()) continue;
          std::string names;
          for (const auto& name : layer_names) names += (names.empty() ? "" : ", ") + name;
          throw InputError("--intensity " + choice + ": class '" + c.name + "' of " + scheme.guideline +
                           " uses the layer '" + layer + "', which " + process + " does not write (" + names + ")");
        }
      }
    }
  }
  return scheme;
}

nlohmann::json add_intensity_layer(gis::LayerWriter& writer, const IntensityScheme& scheme,
                                   const std::map<std::string, const Grid<float>*>& layers) {
  const Grid<float> classes = classify_intensity(scheme, layers);
  const auto& geotransform = classes.spec().geotransform;
  const double cell_area_km2 = std::abs(geotransform[1] * geotransform[5]) / 1e6;
  const auto passages = layers.find("passages");  // rock fall only
  nlohmann::json counts = nlohmann::json::array();
  for (const IntensityClass& c : scheme.classes) {
    const auto cells = std::ranges::count(classes.values(), static_cast<float>(c.value));
    nlohmann::json entry = {{"value", c.value},
                            {"name", c.name},
                            {"label", c.label},
                            {"cells", cells},
                            {"area_km2", static_cast<double>(cells) * cell_area_km2}};
    if (passages != layers.end()) {
      std::int64_t thin = 0;
      for (std::size_t k = 0; k < classes.values().size(); ++k) {
        thin += classes.values()[k] == static_cast<float>(c.value) && passages->second->values()[k] < kQuantilePassages;
      }
      entry["cells_under_" + std::to_string(kQuantilePassages) + "_passages"] = thin;
    }
    counts.push_back(entry);
  }
  gis::LayerDescription layer{"intensity", "Intensity class by " + scheme.guideline, ""};
  layer.style_qml = gis::intensity_style_qml(scheme);
  writer.add(classes, layer);
  return {{"guideline", scheme.guideline}, {"title", scheme.title}, {"source", scheme.source}, {"classes", counts}};
}

nlohmann::json write_layers_with_intensity(gis::LayerWriter& writer, const HazardLayers& layers,
                                           const std::optional<IntensityScheme>& intensity) {
  std::map<std::string, const Grid<float>*> by_name;
  for (const auto& [grid, layer] : layers) {
    writer.add(*grid, layer);
    by_name[layer.name] = grid;
  }
  return intensity ? add_intensity_layer(writer, *intensity, by_name) : nlohmann::json();
}

std::string intensity_summary(const nlohmann::json& entry) {
  std::string text = "Intensity (" + entry["guideline"].get<std::string>() + "):";
  bool first = true;
  for (const auto& c : entry["classes"]) {
    char part[160];
    std::snprintf(part, sizeof part, "%s %s %lld cells (%.3f km2)", first ? "" : ",", c["name"].get<std::string>().c_str(),
                  static_cast<long long>(c["cells"].get<std::int64_t>()), c["area_km2"].get<double>());
    text += part;
    first = false;
  }
  return text;
}

std::vector<std::string> intensity_problems(const nlohmann::json& entry) {
  const std::string key = "cells_under_" + std::to_string(kQuantilePassages) + "_passages";
  std::vector<std::string> lines;
  for (const auto& c : entry["classes"]) {
    if (!c.contains(key)) continue;
    const auto cells = c["cells"].get<std::int64_t>(), thin = c[key].get<std::int64_t>();
    if (cells == 0 || static_cast<double>(thin) <= kThinClassShare * static_cast<double>(cells)) continue;
    char line[400];
    std::snprintf(line, sizeof line,
                  "intensity: %lld of the %lld %s cells (%.0f %%) were passed by fewer than %d rocks, too few for their "
                  "95th percentile of energy: the %s area is uncertain there; more runs (--runs, [run] max_runs) "
                  "settle it",
                  static_cast<long long>(thin), static_cast<long long>(cells), c["name"].get<std::string>().c_str(),
                  100.0 * static_cast<double>(thin) / static_cast<double>(cells), kQuantilePassages,
                  c["name"].get<std::string>().c_str());
    lines.emplace_back(line);
  }
  return lines;
}

}  // namespace talus::cli
