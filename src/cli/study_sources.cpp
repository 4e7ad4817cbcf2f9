#include "study_sources.hpp"

#include <algorithm>

#include "job_output.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/intensity_style.hpp"
#include "talus/gis/layer_writer.hpp"
#include "talus/gis/run_record.hpp"
#include "talus/gis/scene.hpp"

namespace talus::cli {
namespace {

// The source rasters' style: source cells in one colour, the rest transparent.
std::string sources_style_qml() {
  IntensityScheme palette;
  palette.classes.push_back({1, "source", "potential rock-fall source", "#7b3294", {}});
  return gis::intensity_style_qml(palette);
}

nlohmann::ordered_json units_json(const std::array<SlopeUnit, 4>& units) {
  const char* names[] = {"plains", "footslopes", "steep slopes", "rock cliffs"};
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < units.size(); ++k) {
    out.push_back({{"unit", names[k]}, {"share", units[k].weight}, {"mean_deg", units[k].mean}, {"sd_deg", units[k].sd}});
  }
  return out;
}

}  // namespace

SlopeAnalysis analyse_slopes(const Study& study) {
  gis::SceneInputs inputs = study.inputs;
  inputs.release.clear();
  gis::Scene scene = gis::load_scene(inputs);
  SlopeAnalysis analysis{slope_angles(scene.dem.elevation), {}, std::move(scene.lithology)};
  analysis.units = slope_units(analysis.slopes);
  return analysis;
}

DetectedSources detect_sources(const SlopeAnalysis& analysis, const StudyScenario& s) {
  DetectedSources found;
  found.units = analysis.units;
  if (s.source_slope) {
    found.threshold_deg = *s.source_slope;
    found.threshold_from_dem = false;
  } else {
    const std::optional<double> threshold = cliff_threshold(found.units);
    if (!threshold) {
      throw InputError(s.where + ": release = \"auto\": the DEM's slope angles show no rock-cliff unit steeper "
                       "than its steep slopes (Loye et al. 2009); give source_slope (degrees)");
    }
    found.threshold_deg = *threshold;
  }
  found.mask = source_mask(analysis.slopes, found.threshold_deg, analysis.lithology, s.source_lithology);
  found.cells = static_cast<std::size_t>(std::count(found.mask.values().begin(), found.mask.values().end(), 1.0f));
  if (found.cells == 0) {
    throw InputError(s.where + ": release = \"auto\": no cell steeper than " + printf_text("%.1f", found.threshold_deg) +
                     " degrees" + (s.source_lithology.empty() ? "" : " in the classes of source_lithology") +
                     ": no source to release rocks from");
  }
  return found;
}

std::filesystem::path detected_sources_path(const std::filesystem::path& out, const StudyScenario& s) {
  return out / "sources" / (s.name + ".tif");
}

nlohmann::ordered_json write_detected_sources(const Study& study, const std::filesystem::path& out,
                                              const std::vector<std::string>& command_line,
                                              const std::vector<std::optional<DetectedSources>>& detected) {
  gis::LayerWriter writer(out / "sources", {{"TALUS_PROCESS", "rock fall"},
                                            {"TALUS_SCENARIO", "potential sources from the slope (Loye et al. 2009)"}});
  gis::RunRecord record;
  record.set_command_line(command_line);
  nlohmann::ordered_json entries = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < study.scenarios.size(); ++k) {
    if (!detected[k]) continue;
    const StudyScenario& s = study.scenarios[k];
    const DetectedSources& d = *detected[k];
    gis::LayerDescription layer{s.name, "Potential rock-fall sources of " + s.name, ""};
    layer.style_qml = sources_style_qml();
    writer.add(d.mask, layer);
    entries[s.name] = {{"threshold_deg", d.threshold_deg},
                       {"threshold", d.threshold_from_dem ? "the DEM's cliff threshold (Loye et al. 2009)" : "source_slope"},
                       {"lithology_classes", s.source_lithology},
                       {"cells", d.cells},
                       {"area_km2", static_cast<double>(d.cells) * d.mask.spec().cell_area() / 1e6},
                       {"slope_units", units_json(d.units)}};
  }
  record.set("sources", entries);
  record.write(writer.temporary_path("run.json"));
  writer.commit();
  return entries;
}

}  // namespace talus::cli
