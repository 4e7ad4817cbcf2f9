// The envelope of a study's scenarios per process (study_region.hpp; issue 19, item 2).
#include "study_region.hpp"

#include <fstream>
#include <sstream>

#include "mudflow_layers.hpp"
#include "rockfall_layers.hpp"
#include "talus/gis/layer_reader.hpp"
#include "talus/gis/layer_writer.hpp"
#include "talus/gis/run_record.hpp"

namespace talus::cli {
namespace {

// The layers merged per process (the others, counts and energy losses per simulated rock, are
// not an envelope) and their description, with intensity as each scenario writes it.
std::vector<gis::LayerDescription> merged_layers(StudyProcess process) {
  const std::vector<std::string> names =
      process == StudyProcess::rockfall
          ? std::vector<std::string>{"reach_probability", "energy_max", "energy_p95", "jump_height_p95", "velocity_max"}
          : std::vector<std::string>{"flow_depth_max", "velocity_max", "pressure_max", "deposit_depth", "arrival_time"};
  const HazardLayers all = process == StudyProcess::rockfall ? rockfall_hazard_layers(RockfallLayers{})
                                                             : mudflow_hazard_layers(FlowLayers{});
  std::vector<gis::LayerDescription> out;
  for (const std::string& name : names) {
    for (const auto& [grid, layer] : all) {
      if (layer.name == name) out.push_back(layer);
    }
  }
  out.push_back({"intensity", "Intensity class", ""});
  return out;
}

std::string text_of(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// `into` takes, in every valid cell, the larger of its value and `layer`'s, or for the earliest
// arrival the smaller positive one (0: never reached).
void envelope(Grid<float>& into, const Grid<float>& layer, gis::OverviewReduction reduction) {
  for (std::size_t cell = 0; cell < into.size(); ++cell) {
    if (!into.is_valid(cell)) continue;
    const float v = layer[cell];
    if (reduction == gis::OverviewReduction::earliest_positive) {
      if (v > 0.0f && (into[cell] <= 0.0f || v < into[cell])) into[cell] = v;
    } else if (v > into[cell]) {
      into[cell] = v;
    }
  }
}

}  // namespace

nlohmann::ordered_json write_region_layers(const Study& study, const StudyChoices& choices, const JobOutput& output) {
  nlohmann::ordered_json entry = nlohmann::ordered_json::object();
  for (const StudyProcess process : {StudyProcess::rockfall, StudyProcess::mudflow}) {
    std::vector<const StudyScenario*> scenarios;
    for (const StudyScenario& s : study.scenarios) {
      if (s.process == process) scenarios.push_back(&s);
    }
    if (scenarios.empty()) continue;
    const std::string name = to_string(process);
    const std::filesystem::path folder = choices.out / "region" / name;
    gis::LayerWriter writer(folder, {{"TALUS_PROCESS", "study"},
                                     {"TALUS_SCENARIO", "envelope of the study's " + name + " scenarios"}});
    gis::RunRecord record;
    record.set_command_line(choices.command_line);
    nlohmann::ordered_json names = nlohmann::ordered_json::array();
    const std::vector<gis::LayerDescription> layers = merged_layers(process);
    for (gis::LayerDescription layer : layers) {
      const std::filesystem::path first = choices.out / "scenarios" / scenarios.front()->name;
      if (!std::filesystem::exists(first / (layer.name + ".tif"))) continue;  // intensity "none"
      Grid<float> merged = gis::read_layer(first / (layer.name + ".tif"));
      for (std::size_t k = 1; k < scenarios.size(); ++k) {
        envelope(merged, gis::read_layer(choices.out / "scenarios" / scenarios[k]->name / (layer.name + ".tif")),
                 layer.overview);
      }
      layer.style_qml = text_of(first / (layer.name + ".qml"));  // the scenarios' own style
      layer.description += layer.overview == gis::OverviewReduction::earliest_positive
                               ? ", earliest over the scenarios"
                               : ", largest over the scenarios";
      writer.add(merged, layer);
      names.push_back(layer.name);
    }
    nlohmann::ordered_json merged_from = nlohmann::ordered_json::array();
    for (const StudyScenario* s : scenarios) merged_from.push_back(s->name);
    entry[name] = {{"folder", (std::filesystem::path("region") / name).string()}, {"layers", names},
                   {"scenarios", merged_from}};
    record.set("region", entry[name]);
    record.write(writer.temporary_path("run.json"));
    writer.commit();
    output.say("Region layers (" + name + ", envelope of " + std::to_string(scenarios.size()) + " scenario" +
               (scenarios.size() == 1 ? "" : "s") + "): " + folder.string());
  }
  return entry;
}

}  // namespace talus::cli
