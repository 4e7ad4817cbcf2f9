// Intensity guidelines from TOML (intensity_guidelines.hpp); the format is described at the
// top of src/cli/intensity_guidelines.toml.
#include "intensity_guidelines.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include <toml++/toml.h>

#include "intensity_guidelines_text.hpp"
#include "talus/core/errors.hpp"

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

}  // namespace

IntensityScheme intensity_scheme(const std::string& choice, const std::string& process) {
  const std::filesystem::path path(choice);
  if (path.extension() != ".toml") {
    const toml::table& file = built_in_file();
    if (!file[choice].is_table()) {
      std::string names;
      for (const auto& name : guideline_names(file)) names += (names.empty() ? "" : ", ") + name;
      throw InputError("--intensity " + choice + ": not a built-in guideline (" + names +
                       "), none, or a FILE.toml");
    }
    return scheme_of(file, choice, process, "intensity_guidelines.toml");
  }
  const std::string origin = path.string() + " (intensity guideline)";
  toml::table file;
  try {
    file = toml::parse_file(path.string());
  } catch (const toml::parse_error& error) {
    throw InputError(origin + ": line " + std::to_string(error.source().begin.line) + ": " +
                     std::string(error.description()));
  }
  std::string name = file["default"].value<std::string>().value_or("");
  if (name.empty()) {
    const auto names = guideline_names(file);
    if (names.size() != 1) throw InputError(origin + ": holds several guidelines; name one with `default = \"NAME\"`");
    name = names.front();
  }
  return scheme_of(file, name, process, origin);
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
