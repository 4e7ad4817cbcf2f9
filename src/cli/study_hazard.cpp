#include "study_hazard.hpp"

#include <algorithm>
#include <cmath>

#include "intensity_guidelines.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/hazard_zones_writer.hpp"
#include "talus/gis/layer_reader.hpp"
#include "talus/gis/layer_writer.hpp"
#include "talus/gis/run_record.hpp"
#include "talus/hazard/intensity_classes.hpp"

namespace talus::cli {
namespace {

// An empty map on the intensity layer's grid: 0 where valid, nodata where not.
Grid<float> empty_hazard(const Grid<float>& intensity) {
  Grid<float> hazard(intensity.spec(), 0.0f);
  for (std::size_t cell = 0; cell < hazard.size(); ++cell) {
    if (!intensity.is_valid(cell)) hazard[cell] = static_cast<float>(intensity.spec().nodata);
  }
  return hazard;
}

// Cells and area (km2) of each degree of a map.
nlohmann::ordered_json degree_counts(const Grid<float>& hazard, const HazardMatrix& matrix) {
  const double cell_km2 = hazard.spec().cell_area() / 1e6;
  nlohmann::ordered_json counts = nlohmann::ordered_json::array();
  for (const HazardDegree& d : matrix.degrees) {
    const auto cells = std::ranges::count(hazard.values(), static_cast<float>(d.value));
    counts.push_back({{"value", d.value}, {"name", d.name}, {"cells", cells},
                      {"area_km2", static_cast<double>(cells) * cell_km2}});
  }
  return counts;
}

}  // namespace

StudyZoning study_zoning(const Study& study, const std::vector<std::string>& intensity) {
  StudyZoning zoning;
  zoning.guideline = intensity.front();
  for (std::size_t k = 1; k < intensity.size(); ++k) {
    if (intensity[k] != zoning.guideline) {
      throw InputError(study.scenarios[k].where + ": [outputs] intensity " + intensity[k] + " differs from " +
                       zoning.guideline + " of " + study.scenarios.front().name +
                       ": the hazard map needs every scenario's intensity by one guideline");
    }
  }
  if (zoning.guideline == "none") {
    zoning.note = "no hazard map: the scenarios write no intensity layer ([outputs] intensity = \"none\")";
    return zoning;
  }
  zoning.matrix = hazard_matrix(zoning.guideline);
  if (!zoning.matrix) {
    zoning.note = "no hazard map: the intensity guideline " + zoning.guideline + " has no hazard matrix ([NAME.hazard])";
    return zoning;
  }
  for (const StudyScenario& s : study.scenarios) {
    for (const IntensityClass& c : intensity_scheme(zoning.guideline, to_string(s.process)).classes) {
      if (zoning.matrix->degree_values.count(c.name) == 0) {
        throw InputError(s.where + ": the hazard matrix of " + zoning.guideline + " has no row for the intensity class '" +
                         c.name + "'");
      }
    }
  }
  return zoning;
}

nlohmann::ordered_json write_study_hazard(const Study& study, const StudyChoices& choices, const StudyZoning& zoning,
                                          const JobOutput& output) {
  const HazardMatrix& matrix = *zoning.matrix;
  gis::LayerWriter writer(choices.out / "hazard",
                          {{"TALUS_PROCESS", "study"}, {"TALUS_SCENARIO", "hazard degrees by " + matrix.guideline}});
  gis::RunRecord record;
  record.set_command_line(choices.command_line);
  std::optional<Grid<float>> rockfall, mudflow;
  for (const StudyScenario& s : study.scenarios) {
    const std::filesystem::path layer = choices.out / "scenarios" / s.name / "intensity.tif";
    const Grid<float> intensity = gis::read_layer(layer);
    std::optional<Grid<float>>& map = s.process == StudyProcess::rockfall ? rockfall : mudflow;
    if (!map) map = empty_hazard(intensity);
    const std::filesystem::path reach_layer = choices.out / "scenarios" / s.name / "reach_probability.tif";
    const bool with_reach = s.process == StudyProcess::rockfall && study.rockfall_reach;
    const std::optional<Grid<float>> reach = with_reach ? std::optional(gis::read_layer(reach_layer)) : std::nullopt;
    raise_hazard(*map, matrix, intensity_scheme(zoning.guideline, to_string(s.process)), intensity,
                 s.return_period_years, reach ? &*reach : nullptr);
    record.add_input(s.name, layer, nullptr);
    if (reach) record.add_input(s.name + " reach", reach_layer, nullptr);
  }
  Grid<float> both = rockfall ? *rockfall : *mudflow;
  if (rockfall && mudflow) {
    for (std::size_t cell = 0; cell < both.size(); ++cell) {
      if (both.is_valid(cell)) both[cell] = std::max(both[cell], (*mudflow)[cell]);
    }
  }
  nlohmann::ordered_json maps = nlohmann::ordered_json::object();
  // The rule that turned a rock fall's return period into a cell's probability changes the map
  // (docs/study.md, "Hazard map"), so the title, the legend heading and the metadata name it.
  const std::string rule = study.rockfall_reach ? "; rock fall per cell: return period / reach probability"
                                                : "; rock fall per cell: return period where rocks reach (onset)";
  const auto add = [&](const Grid<float>& map, const std::string& name, const std::string& what, bool with_rockfall) {
    gis::LayerDescription layer{name, "Hazard degree" + what + " (" + matrix.guideline + (with_rockfall ? rule : "") + ")", ""};
    layer.style_qml = gis::hazard_style_qml(matrix);
    writer.add(map, layer);
    maps[name] = degree_counts(map, matrix);
  };
  add(both, "hazard", "", rockfall.has_value());
  if (rockfall) add(*rockfall, "hazard_rockfall", ", rock fall", true);
  if (mudflow) add(*mudflow, "hazard_mudflow", ", mud flow", false);
  const gis::ZoneCounts zones = gis::add_hazard_zones(writer, both, matrix, study.zones);
  nlohmann::ordered_json probabilities = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < matrix.probabilities.size(); ++k) {
    probabilities.push_back({{"name", matrix.probabilities[k]},
                             {"return_period_up_to_years",
                              k < matrix.return_period_limits.size() ? nlohmann::ordered_json(matrix.return_period_limits[k])
                                                                     : nlohmann::ordered_json(nullptr)}});
  }
  const nlohmann::ordered_json entry = {{"guideline", matrix.guideline}, {"source", matrix.source},
                                        {"rockfall_probability", study.rockfall_reach ? "reach" : "onset"},
                                        {"probabilities", probabilities}, {"maps", maps},
                                        {"zones", {{"minimum_area_m2", study.zones.minimum_area_m2},
                                                   {"smoothed", study.zones.smooth},
                                                   {"cell_patches", zones.cell_patches},
                                                   {"polygons", zones.zones}}}};
  record.set("hazard", entry);
  record.write(writer.temporary_path("run.json"));
  writer.commit();
  std::string line = "Hazard map (" + matrix.guideline + "):";
  for (const auto& d : maps["hazard"]) {
    line += printf_text(" %s %.3f km2,", d["name"].get<std::string>().c_str(), d["area_km2"].get<double>());
  }
  line.pop_back();
  output.say(line + "; in " + (choices.out / "hazard").string() + " (hazard.tif, hazard_zones.gpkg: " +
             std::to_string(zones.zones) + " zones of at least " + printf_text("%g", study.zones.minimum_area_m2) +
             " m2 from " + std::to_string(zones.cell_patches) + " patches of cells" +
             (study.zones.smooth ? ", smoothed)" : ")"));
  return entry;
}

}  // namespace talus::cli
