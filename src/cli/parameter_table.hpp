// Parameters are data (docs/architecture.md section 5): every tunable number of a run is listed once
// here with its section, unit and meaning; the scenario TOML maps onto it 1:1, `talus params`
// prints it as JSON, and run.json records the resolved values.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

namespace talus::cli {

// The most threads a run may be given (`[run] threads`, --threads); 0 asks for all cores.
inline constexpr double kMaxThreads = 1024;

// A count the program may choose itself: "auto" or a whole number (`[run] runs`, --runs).
struct CountOrAuto {
  bool automatic = false;
  std::uint64_t count = 0;
};

// "auto" or the digits of a whole number; anything else is InputError naming `where` (an option
// or a scenario key) and the text.
CountOrAuto parse_count_or_auto(const std::string& where, const std::string& text);

class ParameterTable {
 public:
  using Target = std::variant<double*, int*, std::uint64_t*, std::string*, bool*, CountOrAuto*>;
  // Where a value came from, lowest first. A source sets only the values that came from a lower
  // one, so a material preset < the scenario file < a command-line flag, whatever the order in
  // which they are applied.
  enum class Origin { built_in, material, scenario, command_line };
  // The values a numeric parameter may take (issue 18, item 1), in its unit; a value must also be
  // finite. Printed by `talus params` and checked by check_ranges().
  struct Range {
    Range(double min_value, double max_value, bool min_is_exclusive = false, bool max_is_exclusive = false,
          std::optional<double> off_value = std::nullopt, std::string off_meaning = "")
        : min(min_value), max(max_value), min_exclusive(min_is_exclusive), max_exclusive(max_is_exclusive),
          off(off_value), off_means(std::move(off_meaning)) {}
    double min, max;
    bool min_exclusive, max_exclusive;
    std::optional<double> off;  // one more value allowed outside [min, max], e.g. 0,
    std::string off_means;      // and what it means: "off", "all cores"
  };
  struct Entry {
    std::string section, name, unit, description;
    Target target;
    Origin origin = Origin::built_in;
    std::optional<Range> range;
    std::string given_by;  // where the value came from, for messages: "--runs", "F.toml (scenario): [run] runs"
  };

  void add(std::string section, std::string name, std::string unit, std::string description, Target target,
           std::optional<Range> range = std::nullopt);
  // A key that sources may no longer name: naming it is InputError with `instead`, the line that
  // says what to give now.
  void retire(std::string section, std::string name, std::string instead);
  // {section: {name: value}}: the resolved values, for run.json.
  nlohmann::json values() const;
  // [{section, name, unit, description, default}], for `talus params`.
  nlohmann::json describe() const;
  // Marks an entry as given on the command line by `option` (e.g. "--runs"), so that no other
  // source overrides it.
  void pin(const std::string& section, const std::string& name, const std::string& option = "");
  // Every value with a range lies in it, or InputError names where it came from, the value and
  // the range: `--runs 0: expected ...`, `F.toml (scenario): [fast_bounce] gravity -9.81: ...`.
  void check_ranges() const;
  // A rule between values that a range cannot say (merge_threshold below split_threshold): unless
  // `ok`, InputError naming where the value came from, `value` and `expected`.
  void require(bool ok, const std::string& section, const std::string& name, const std::string& value,
               const std::string& expected) const;
  // How messages name a parameter: its flag, "F.toml (scenario): [section] name" or "[section] name".
  std::string where(const std::string& section, const std::string& name) const;
  bool given_on_command_line(const std::string& section, const std::string& name) const;
  // Sets the values a TOML table gives by [section] key from `origin`, except those that came
  // from a higher one; unknown sections or keys, retired keys and values of the wrong type are
  // InputError naming `source` (e.g. "flow.toml (scenario)") and the key.
  void apply(const toml::table& sections, Origin origin, const std::string& source);
  // apply() with a scenario file's sections, except `ignored_sections`.
  void apply_scenario(const std::filesystem::path& scenario, const std::vector<std::string>& ignored_sections);
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  struct RetiredKey {
    std::string section, name, instead;
  };
  std::vector<Entry> entries_;
  std::vector<RetiredKey> retired_;
};

}  // namespace talus::cli
