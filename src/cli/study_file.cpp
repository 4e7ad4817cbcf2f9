#include "study_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "job_output.hpp"
#include "talus/core/errors.hpp"
#include "toml_file.hpp"

namespace talus::cli {
namespace {

constexpr double kLongestReturnPeriod = 1e6;  // years

// The keys of a scenario that are the study's own; every other key is a subcommand section.
const std::set<std::string> kScenarioKeys = {"name",          "release",          "erodible",     "scenario",
                                             "return_period", "annual_frequency", "source_slope", "source_lithology"};

std::string text_key(const toml::table& table, const std::string& key, const std::string& where, bool required) {
  const toml::node* node = table.get(key);
  if (node == nullptr) {
    if (required) throw InputError(where + ": '" + key + "' is missing");
    return "";
  }
  const auto text = node->value<std::string>();
  if (!text || text->empty()) throw InputError(where + ": '" + key + "' must be a non-empty string");
  return *text;
}

std::filesystem::path path_key(const toml::table& table, const std::string& key, const std::string& where,
                               const std::filesystem::path& folder, bool required) {
  const std::string text = text_key(table, key, where, required);
  if (text.empty()) return {};
  const std::filesystem::path path(text);
  return path.is_absolute() ? path : folder / path;
}

// A scenario's name becomes a folder: letters, digits, '-', '_' and '.', not starting with '.'.
void check_name(const std::string& name, const std::string& where) {
  const bool safe = !name.empty() && name.size() <= 100 && name.front() != '.' &&
                    std::all_of(name.begin(), name.end(), [](char c) {
                      return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
                    });
  if (!safe) {
    throw InputError(where + ": name '" + name + "': use 1 to 100 letters, digits, '-', '_' or '.' (not first)");
  }
}

// return_period (years) or annual_frequency (1/year), exactly one of them.
double return_period(const toml::table& table, const std::string& where) {
  const toml::node* period = table.get("return_period");
  const toml::node* frequency = table.get("annual_frequency");
  if ((period == nullptr) == (frequency == nullptr)) {
    throw InputError(where + ": give one of 'return_period' (years) and 'annual_frequency' (1/year)");
  }
  const auto value = (period ? period : frequency)->value<double>();
  const std::string key = period ? "return_period" : "annual_frequency";
  if (!value || !std::isfinite(*value) || !(*value > 0.0)) throw InputError(where + ": '" + key + "' must be a number > 0");
  const double years = period ? *value : 1.0 / *value;
  if (!(years >= 1.0 / 365.25 && years <= kLongestReturnPeriod)) {
    throw InputError(where + ": '" + key + "' gives a return period of " + std::to_string(years) +
                     " years: expected 1 day to 1000000 years");
  }
  return years;
}

// source_slope (degrees, 1-89) and source_lithology (class codes) of a rock fall with release = "auto".
void read_source_keys(const toml::table& table, StudyScenario& s) {
  if (const toml::node* slope = table.get("source_slope")) {
    const auto degrees = slope->value<double>();
    if (!degrees || !(*degrees >= 1.0 && *degrees <= 89.0)) {
      throw InputError(s.where + ": 'source_slope' must be an angle of 1 to 89 degrees");
    }
    s.source_slope = *degrees;
  }
  if (const toml::node* classes = table.get("source_lithology")) {
    const toml::array* list = classes->as_array();
    if (list == nullptr || list->empty()) throw InputError(s.where + ": 'source_lithology' must list lithology class codes");
    for (const toml::node& item : *list) {
      const auto code = item.value<std::int64_t>();
      if (!code || *code < 0 || *code > 65535) throw InputError(s.where + ": 'source_lithology' must list class codes 0-65535");
      s.source_lithology.insert(static_cast<int>(*code));
    }
  }
}

StudyScenario read_scenario(const toml::table& table, StudyProcess process, const std::string& file_name,
                            const std::filesystem::path& folder, std::size_t index) {
  StudyScenario s;
  s.process = process;
  const std::string array = std::string("[[") + to_string(process) + "]]";
  s.where = file_name + ": " + array + " " + std::to_string(index + 1);
  s.name = text_key(table, "name", s.where, true);
  s.where = file_name + ": " + array + " " + s.name;
  check_name(s.name, s.where);
  const bool automatic = process == StudyProcess::rockfall && text_key(table, "release", s.where, true) == "auto";
  if (automatic) {
    s.detect_sources = true;
    read_source_keys(table, s);
  } else {
    s.release = path_key(table, "release", s.where, folder, true);
    if (table.contains("source_slope") || table.contains("source_lithology")) {
      throw InputError(s.where + ": 'source_slope' and 'source_lithology' are for release = \"auto\" (rock fall)");
    }
  }
  s.scenario = path_key(table, "scenario", s.where, folder, false);
  if (process == StudyProcess::mudflow) {
    s.erodible = path_key(table, "erodible", s.where, folder, false);
  } else if (table.contains("erodible")) {
    throw InputError(s.where + ": 'erodible' is for mud-flow scenarios");
  }
  s.return_period_years = return_period(table, s.where);
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    if (kScenarioKeys.count(name) > 0) continue;
    if (!node.is_table()) {
      throw InputError(s.where + ": unknown key '" + name + "' (a scenario has name, release, scenario, " +
                       "return_period or annual_frequency" + (process == StudyProcess::mudflow ? ", erodible" : "") +
                       ", and the sections of talus " + to_string(process) + ")");
    }
    s.parameters.insert(name, *node.as_table());
  }
  return s;
}

}  // namespace

const char* to_string(StudyProcess process) { return process == StudyProcess::rockfall ? "rockfall" : "mudflow"; }

Study read_study(const std::filesystem::path& file) {
  const std::string name = file.string() + " (study)";
  const toml::table root = read_toml_file(file, name);
  Study study;
  study.file = file;
  const std::filesystem::path folder = file.parent_path();
  for (const auto& [key, node] : root) {
    const std::string section(key.str());
    if (section != "inputs" && section != "hazard" && section != "rockfall" && section != "mudflow") {
      throw InputError(name + ": unknown section '" + section +
                       "' (a study has [inputs], [hazard], [[rockfall]] and [[mudflow]])");
    }
  }
  if (const toml::node* hazard_node = root.get("hazard")) {
    const toml::table* hazard = hazard_node->as_table();
    if (hazard == nullptr) throw InputError(name + ": 'hazard' must be a table, [hazard]");
    for (const auto& [key, node] : *hazard) {
      if (key.str() != "rockfall_probability" && key.str() != "minimum_zone_m2" && key.str() != "smooth_zones") {
        throw InputError(name + ": [hazard]: unknown key '" + std::string(key.str()) +
                         "' (rockfall_probability, minimum_zone_m2, smooth_zones)");
      }
    }
    if (const toml::node* area = hazard->get("minimum_zone_m2")) {
      const std::optional<double> value = area->is_number() ? area->value<double>() : std::nullopt;
      if (!value || !(*value >= 0.0 && *value <= 1e6)) {
        const std::string given = value ? printf_text(" %g", *value) : "";
        throw InputError(name + ": [hazard] minimum_zone_m2" + given + ": expected a number of 0-1000000 m2");
      }
      study.zones.minimum_area_m2 = *value;
    }
    if (const toml::node* smooth = hazard->get("smooth_zones")) {
      if (!smooth->is_boolean()) throw InputError(name + ": [hazard] smooth_zones: must be true or false");
      study.zones.smooth = smooth->as_boolean()->get();
    }
    const std::string choice = text_key(*hazard, "rockfall_probability", name + ": [hazard]", false);
    if (!choice.empty() && choice != "reach" && choice != "onset") {
      throw InputError(name + ": [hazard] rockfall_probability " + choice + ": use reach or onset");
    }
    study.rockfall_reach = choice != "onset";
  }
  const toml::table* inputs = root["inputs"].as_table();
  if (inputs == nullptr) throw InputError(name + ": [inputs] with the region's dem is missing");
  const std::string where = name + ": [inputs]";
  for (const auto& [key, node] : *inputs) {
    const std::string input(key.str());
    if (input != "dem" && input != "lithology" && input != "vegetation" && input != "materials" && input != "crs") {
      throw InputError(where + ": unknown key '" + input + "' (dem, lithology, vegetation, materials, crs)");
    }
  }
  study.inputs.dem = path_key(*inputs, "dem", where, folder, true);
  study.inputs.lithology = path_key(*inputs, "lithology", where, folder, false);
  study.inputs.vegetation = path_key(*inputs, "vegetation", where, folder, false);
  study.inputs.materials = path_key(*inputs, "materials", where, folder, false);
  study.inputs.crs = text_key(*inputs, "crs", where, false);
  std::set<std::string> names;
  for (const StudyProcess process : {StudyProcess::rockfall, StudyProcess::mudflow}) {
    const toml::node_view<const toml::node> list = root[to_string(process)];
    if (!list) continue;
    const toml::array* array = list.as_array();
    if (array == nullptr || !array->is_array_of_tables()) {
      throw InputError(name + ": '" + to_string(process) + "' must be an array of tables, [[" + to_string(process) + "]]");
    }
    for (std::size_t k = 0; k < array->size(); ++k) {
      StudyScenario s = read_scenario(*array->get(k)->as_table(), process, name, folder, k);
      if (!names.insert(s.name).second) throw InputError(s.where + ": a second scenario with this name");
      study.scenarios.push_back(std::move(s));
    }
  }
  if (study.scenarios.empty()) throw InputError(name + ": no scenario: add [[rockfall]] or [[mudflow]] tables");
  return study;
}

}  // namespace talus::cli
