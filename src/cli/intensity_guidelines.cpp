// Intensity guidelines from TOML (intensity_guidelines.hpp); the format is described at the
// top of src/cli/intensity_guidelines.toml.
#include "intensity_guidelines.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include <toml++/toml.h>

#include "intensity_guidelines_text.hpp"
#include "talus/core/errors.hpp"
#include "toml_file.hpp"

namespace talus::cli {
namespace {

std::string trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return std::string(text.substr(first, last - first + 1));
}

// "LAYER > NUMBER", "LAYER >= NUMBER" or "LAYER * LAYER > NUMBER".
IntensityThreshold parse_threshold(const std::string& text, const std::string& where) {
  const auto op = text.find('>');
  if (op == std::string::npos) throw InputError(where + ": '" + text + "' is not LAYER > NUMBER");
  IntensityThreshold threshold;
  threshold.inclusive = op + 1 < text.size() && text[op + 1] == '=';
  const std::string number = trimmed(std::string_view(text).substr(op + (threshold.inclusive ? 2 : 1)));
  char* end = nullptr;
  threshold.above = std::strtod(number.c_str(), &end);
  if (number.empty() || *end != '\0' || !std::isfinite(threshold.above))
    throw InputError(where + ": '" + number + "' in '" + text + "' is not a finite number");
  std::string_view names = std::string_view(text).substr(0, op);
  while (true) {
    const auto star = names.find('*');
    const std::string name = trimmed(names.substr(0, star));
    if (name.empty() || name.find(' ') != std::string::npos)
      throw InputError(where + ": '" + text + "' does not name a layer before '>'");
    threshold.layers.push_back(name);
    if (star == std::string_view::npos) break;
    names.remove_prefix(star + 1);
  }
  return threshold;
}

// "A > 1 and B > 2": the thresholds that must all hold.
std::vector<IntensityThreshold> parse_alternative(const std::string& text, const std::string& where) {
  std::vector<IntensityThreshold> thresholds;
  std::size_t start = 0;
  while (true) {
    const auto joint = text.find(" and ", start);
    thresholds.push_back(parse_threshold(text.substr(start, joint - start), where));
    if (joint == std::string::npos) break;
    start = joint + 5;
  }
  return thresholds;
}

bool is_colour(const std::string& text) {
  return text.size() == 7 && text[0] == '#' &&
         text.find_first_not_of("0123456789abcdefABCDEF", 1) == std::string::npos;
}

IntensityScheme scheme_of(const toml::table& file, const std::string& name, const std::string& process,
                          const std::string& origin) {
  const toml::table* guideline = file[name].as_table();
  if (guideline == nullptr) throw InputError(origin + ": no guideline named '" + name + "'");
  IntensityScheme scheme;
  scheme.guideline = name;
  scheme.title = (*guideline)["title"].value<std::string>().value_or(name);
  scheme.source = (*guideline)["source"].value<std::string>().value_or("");
  const toml::array* classes = (*guideline)[process].as_array();
  if (classes == nullptr || classes->empty())
    throw InputError(origin + ": guideline '" + name + "' has no [[" + name + "." + process + "]] classes");
  for (const toml::node& node : *classes) {
    const toml::table* entry = node.as_table();
    const std::string where = origin + ": [[" + name + "." + process + "]] class " + std::to_string(scheme.classes.size() + 1);
    if (entry == nullptr) throw InputError(where + ": not a table");
    IntensityClass c;
    const auto value = (*entry)["value"].value<std::int64_t>();
    if (!value || *value < 1 || *value > 255) throw InputError(where + ": `value` must be an integer 1-255");
    c.value = static_cast<int>(*value);
    c.name = (*entry)["name"].value<std::string>().value_or("");
    c.label = (*entry)["label"].value<std::string>().value_or(c.name);
    c.colour = (*entry)["colour"].value<std::string>().value_or("");
    if (c.name.empty()) throw InputError(where + ": `name` is missing");
    if (!is_colour(c.colour)) throw InputError(where + " (" + c.name + "): `colour` must be #rrggbb");
    const toml::array* when = (*entry)["when"].as_array();
    if (when == nullptr || when->empty()) throw InputError(where + " (" + c.name + "): `when` must list conditions");
    for (const toml::node& alternative : *when) {
      const auto text = alternative.value<std::string>();
      if (!text) throw InputError(where + " (" + c.name + "): every `when` entry must be a string");
      c.when.push_back(parse_alternative(*text, where + " (" + c.name + ")"));
    }
    for (const IntensityClass& earlier : scheme.classes) {
      if (earlier.value == c.value) throw InputError(where + " (" + c.name + "): value " + std::to_string(c.value) + " is used twice");
    }
    scheme.classes.push_back(std::move(c));
  }
  return scheme;
}

const toml::table& built_in_file() {
  static const toml::table file =
      toml::parse(std::string_view(kIntensityGuidelinesToml), std::string_view("intensity_guidelines.toml"));
  return file;
}

// The guidelines of a file: every top-level table.
std::vector<std::string> guideline_names(const toml::table& file) {
  std::vector<std::string> names;
  for (const auto& [key, node] : file)
    if (node.is_table()) names.emplace_back(key.str());
  return names;
}

// The guideline `choice` names: a built-in one, or FILE.toml's `default` or only guideline.
struct ChosenGuideline {
  toml::table file;
  std::string name;
  std::string origin;  // for messages: "intensity_guidelines.toml", "F.toml (intensity guideline)"
};

ChosenGuideline chosen_guideline(const std::string& choice) {
  const std::filesystem::path path(choice);
  if (path.extension() != ".toml") {
    const toml::table& file = built_in_file();
    if (!file[choice].is_table()) {
      std::string names;
      for (const auto& name : guideline_names(file)) names += (names.empty() ? "" : ", ") + name;
      throw InputError("--intensity " + choice + ": not a built-in guideline (" + names +
                       "), none, or a FILE.toml");
    }
    return {file, choice, "intensity_guidelines.toml"};
  }
  ChosenGuideline chosen;
  chosen.origin = path.string() + " (intensity guideline)";
  chosen.file = read_toml_file(path, chosen.origin);
  chosen.name = chosen.file["default"].value<std::string>().value_or("");
  if (chosen.name.empty()) {
    const auto names = guideline_names(chosen.file);
    if (names.size() != 1) throw InputError(chosen.origin + ": holds several guidelines; name one with `default = \"NAME\"`");
    chosen.name = names.front();
  }
  return chosen;
}

// The strings of an array, or InputError naming `where`.
std::vector<std::string> string_list(const toml::node_view<const toml::node>& node, const std::string& where) {
  const toml::array* array = node.as_array();
  if (array == nullptr || array->empty()) throw InputError(where + " must be a list of strings");
  std::vector<std::string> out;
  for (const toml::node& item : *array) {
    const auto text = item.value<std::string>();
    if (!text) throw InputError(where + " must be a list of strings");
    out.push_back(*text);
  }
  return out;
}

HazardMatrix matrix_of(const toml::table& hazard, const std::string& name, const std::string& origin) {
  const std::string where = origin + ": [" + name + ".hazard]";
  HazardMatrix matrix;
  matrix.guideline = name;
  matrix.source = hazard["source"].value<std::string>().value_or("");
  matrix.probabilities = string_list(hazard["probabilities"], where + " probabilities");
  const toml::array* limits = hazard["return_period_limits"].as_array();
  if (limits == nullptr || limits->size() + 1 != matrix.probabilities.size()) {
    throw InputError(where + " return_period_limits must list one return period (years) fewer than the probabilities");
  }
  for (const toml::node& item : *limits) {
    const auto years = item.value<double>();
    if (!years || !std::isfinite(*years) || *years <= 0.0 ||
        (!matrix.return_period_limits.empty() && *years <= matrix.return_period_limits.back())) {
      throw InputError(where + " return_period_limits must be increasing return periods (years) > 0");
    }
    matrix.return_period_limits.push_back(*years);
  }
  const toml::array* degrees = hazard["degrees"].as_array();
  if (degrees == nullptr || degrees->empty()) throw InputError(where + ": no [[" + name + ".hazard.degrees]]");
  for (const toml::node& node : *degrees) {
    const toml::table* entry = node.as_table();
    const std::string at = where + " degree " + std::to_string(matrix.degrees.size() + 1);
    if (entry == nullptr) throw InputError(at + ": not a table");
    HazardDegree d;
    const auto value = (*entry)["value"].value<std::int64_t>();
    if (!value || *value < 1 || *value > 255) throw InputError(at + ": `value` must be an integer 1-255");
    d.value = static_cast<int>(*value);
    d.name = (*entry)["name"].value<std::string>().value_or("");
    d.label = (*entry)["label"].value<std::string>().value_or(d.name);
    d.colour = (*entry)["colour"].value<std::string>().value_or("");
    if (d.name.empty() || d.name == "none") throw InputError(at + ": `name` is missing or \"none\"");
    if (!is_colour(d.colour)) throw InputError(at + " (" + d.name + "): `colour` must be #rrggbb");
    for (const HazardDegree& earlier : matrix.degrees) {
      if (earlier.value == d.value || earlier.name == d.name) throw InputError(at + " (" + d.name + "): used twice");
    }
    matrix.degrees.push_back(std::move(d));
  }
  const toml::table* rows = hazard["matrix"].as_table();
  if (rows == nullptr || rows->empty()) throw InputError(where + ": no [" + name + ".hazard.matrix]");
  for (const auto& [key, node] : *rows) {
    const std::string row_where = where + " matrix " + std::string(key.str());
    const std::vector<std::string> names = string_list(toml::node_view<const toml::node>(&node), row_where);
    if (names.size() != matrix.probabilities.size()) {
      throw InputError(row_where + ": one degree per probability class (" + std::to_string(matrix.probabilities.size()) + ")");
    }
    std::vector<int> values;
    for (const std::string& degree : names) {
      const auto found = std::find_if(matrix.degrees.begin(), matrix.degrees.end(),
                                      [&](const HazardDegree& d) { return d.name == degree; });
      if (degree != "none" && found == matrix.degrees.end()) throw InputError(row_where + ": no degree named '" + degree + "'");
      values.push_back(degree == "none" ? 0 : found->value);
    }
    matrix.degree_values[std::string(key.str())] = values;
  }
  return matrix;
}

}  // namespace

IntensityScheme intensity_scheme(const std::string& choice, const std::string& process) {
  const ChosenGuideline chosen = chosen_guideline(choice);
  return scheme_of(chosen.file, chosen.name, process, chosen.origin);
}

std::optional<HazardMatrix> hazard_matrix(const std::string& choice) {
  const ChosenGuideline chosen = chosen_guideline(choice);
  const toml::table* hazard = chosen.file[chosen.name]["hazard"].as_table();
  if (hazard == nullptr) return std::nullopt;
  return matrix_of(*hazard, chosen.name, chosen.origin);
}

nlohmann::json built_in_intensity_guidelines() {
  const toml::table& file = built_in_file();
  nlohmann::json out = {{"default", file["default"].value<std::string>().value_or("")}, {"guidelines", nlohmann::json::object()}};
  for (const auto& name : guideline_names(file)) {
    out["guidelines"][name] = {{"title", file[name]["title"].value<std::string>().value_or("")},
                               {"source", file[name]["source"].value<std::string>().value_or("")}};
  }
  return out;
}

}  // namespace talus::cli
