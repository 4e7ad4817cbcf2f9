// The parameter table behind scenario files, `talus params` and run.json (docs/architecture.md section 5).
#include "parameter_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "talus/core/errors.hpp"
#include "toml_file.hpp"

namespace talus::cli {
namespace {

nlohmann::json value_of(const ParameterTable::Target& target) {
  return std::visit(
      [](auto* value) {
        using T = std::remove_pointer_t<decltype(value)>;
        if constexpr (std::is_same_v<T, CountOrAuto>) {
          return value->automatic ? nlohmann::json("auto") : nlohmann::json(value->count);
        } else {
          return nlohmann::json(*value);
        }
      },
      target);
}

}  // namespace

CountOrAuto parse_count_or_auto(const std::string& where, const std::string& text) {
  if (text == "auto") return {true, 0};
  const bool digits = !text.empty() && text.size() <= 18 && text.find_first_not_of("0123456789") == std::string::npos;
  if (!digits) throw InputError(where + " " + text + ": expected a whole number or auto");
  return {false, std::stoull(text)};
}

void ParameterTable::add(std::string section, std::string name, std::string unit, std::string description, Target target,
                         std::optional<Range> range) {
  entries_.push_back({std::move(section), std::move(name), std::move(unit), std::move(description), target,
                      Origin::built_in, range, ""});
}

void ParameterTable::retire(std::string section, std::string name, std::string instead) {
  retired_.push_back({std::move(section), std::move(name), std::move(instead)});
}

void ParameterTable::pin(const std::string& section, const std::string& name, const std::string& option) {
  for (auto& e : entries_) {
    if (e.section != section || e.name != name) continue;
    e.origin = Origin::command_line;
    e.given_by = option.empty() ? "[" + section + "] " + name : option;
  }
}

void ParameterTable::check_ranges() const {
  for (const auto& e : entries_) {
    if (!e.range) continue;
    std::optional<double> value;
    std::string value_text;  // as the user wrote it: integers in digits, not "1e+12"
    std::visit(
        [&](auto* target) {
          using T = std::remove_pointer_t<decltype(target)>;
          if constexpr (std::is_same_v<T, CountOrAuto>) {
            if (!target->automatic) value = static_cast<double>(target->count);
            value_text = std::to_string(target->count);
          } else if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
            value = static_cast<double>(*target);
            value_text = std::to_string(*target);
          } else if constexpr (std::is_floating_point_v<T>) {
            value = *target;
            std::ostringstream text;
            text.precision(10);
            text << *target;
            value_text = text.str();
          }
        },
        e.target);
    if (!value) continue;
    const Range& r = *e.range;
    const bool in_range = (r.min_exclusive ? *value > r.min : *value >= r.min) &&
                          (r.max_exclusive ? *value < r.max : *value <= r.max);
    const bool inside = std::isfinite(*value) && (in_range || (r.off && *value == *r.off));
    if (inside) continue;
    std::ostringstream expected;
    expected.precision(10);
    expected << "expected ";
    if (r.off) expected << *r.off << (r.off_means.empty() ? "" : " (" + r.off_means + ")") << " or ";
    if (r.min_exclusive || r.max_exclusive) {
      expected << (r.min_exclusive ? "> " : ">= ") << r.min << " and " << (r.max_exclusive ? "< " : "<= ") << r.max;
    } else {
      expected << r.min << "-" << r.max;
    }
    if (!e.unit.empty() && e.unit != "-") expected << " " << e.unit;
    throw InputError(where(e.section, e.name) + " " + value_text + ": " + expected.str());
  }
}

void ParameterTable::require(bool ok, const std::string& section, const std::string& name, const std::string& value,
                             const std::string& expected) const {
  if (!ok) throw InputError(where(section, name) + " " + value + ": " + expected);
}

std::string ParameterTable::where(const std::string& section, const std::string& name) const {
  for (const auto& e : entries_) {
    if (e.section == section && e.name == name && !e.given_by.empty()) return e.given_by;
  }
  return "[" + section + "] " + name;
}

bool ParameterTable::given_on_command_line(const std::string& section, const std::string& name) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) {
    return e.section == section && e.name == name && e.origin == Origin::command_line;
  });
}

nlohmann::json ParameterTable::values() const {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& e : entries_) out[e.section][e.name] = value_of(e.target);
  return out;
}

nlohmann::json ParameterTable::describe() const {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : entries_) {
    nlohmann::json entry = {{"section", e.section}, {"name", e.name},           {"unit", e.unit},
                            {"description", e.description}, {"default", value_of(e.target)}};
    if (e.range) {
      entry["range"] = {{"min", e.range->min},
                        {"max", e.range->max},
                        {"min_exclusive", e.range->min_exclusive},
                        {"max_exclusive", e.range->max_exclusive}};
      if (e.range->off) {
        entry["range"]["off"] = *e.range->off;
        entry["range"]["off_means"] = e.range->off_means;
      }
    }
    out.push_back(std::move(entry));
  }
  return out;
}

void ParameterTable::apply(const toml::table& sections, Origin origin, const std::string& source) {
  for (const auto& [section_key, section_node] : sections) {
    const std::string section(section_key.str());
    const toml::table* section_table = section_node.as_table();
    const bool known_section = std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.section == section; });
    if (section_table == nullptr || !known_section) throw InputError(source + ": unknown section [" + section + "]");
    for (const auto& item : *section_table) {
      // Named, not a structured binding: clang 14 cannot capture those in the lambda below.
      const toml::key& key = item.first;
      const toml::node& node = item.second;
      const std::string where = "[" + section + "] " + std::string(key.str());
      const auto retired = std::find_if(retired_.begin(), retired_.end(),
                                        [&](const RetiredKey& r) { return r.section == section && r.name == key.str(); });
      if (retired != retired_.end()) throw InputError(source + ": " + where + ": " + retired->instead);
      auto entry = std::find_if(entries_.begin(), entries_.end(),
                                [&](const Entry& e) { return e.section == section && e.name == key.str(); });
      if (entry == entries_.end()) throw InputError(source + ": unknown key '" + std::string(key.str()) + "' in [" + section + "]");
      const bool keep = entry->origin >= origin;
      std::visit(
          [&](auto* value) {
            using T = std::remove_pointer_t<decltype(value)>;
            if constexpr (std::is_same_v<T, std::string>) {
              const auto text = node.value<std::string>();
              if (!text) throw InputError(source + ": " + where + " must be a string");
              if (!keep) *value = *text;
            } else if constexpr (std::is_same_v<T, double>) {
              const auto number = node.value<double>();
              if (!number) throw InputError(source + ": " + where + " must be a number");
              if (!keep) *value = *number;
            } else if constexpr (std::is_same_v<T, CountOrAuto>) {
              // A TOML integer, or a string as the command line takes it ("auto", "100").
              const auto integer = node.value<std::int64_t>();
              const auto text = node.value<std::string>();
              if (integer ? *integer < 0 : !text) {
                throw InputError(source + ": " + where + " must be a whole number or \"auto\"");
              }
              const CountOrAuto parsed = integer ? CountOrAuto{false, static_cast<std::uint64_t>(*integer)}
                                                 : parse_count_or_auto(source + ": " + where, *text);
              if (!keep) *value = parsed;
            } else if constexpr (std::is_same_v<T, bool>) {
              // Only a TOML boolean: toml++ would read 1 or 3 as true.
              const auto* flag = node.as_boolean();
              if (!flag) throw InputError(source + ": " + where + " must be true or false");
              if (!keep) *value = flag->get();
            } else {
              const auto integer = node.value<std::int64_t>();
              // No wrap-around: a value the target type cannot hold is refused, not cast.
              if (!integer || *integer < 0 || static_cast<std::uint64_t>(*integer) > std::numeric_limits<T>::max())
                throw InputError(source + ": " + where + " must be a non-negative integer of at most " +
                                 std::to_string(std::numeric_limits<T>::max()));
              if (!keep) *value = static_cast<T>(*integer);
            }
          },
          entry->target);
      if (!keep) {
        entry->origin = origin;
        entry->given_by = source + ": " + where;
      }
    }
  }
}

void ParameterTable::apply_scenario(const std::filesystem::path& scenario, const std::vector<std::string>& ignored_sections) {
  const std::string name = scenario.string() + " (scenario)";
  toml::table table = read_toml_file(scenario, name);
  for (const std::string& section : ignored_sections) table.erase(section);
  apply(table, Origin::scenario, name);
}

}  // namespace talus::cli
