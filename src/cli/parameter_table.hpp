// Parameters are data (DESIGN.md section 1): every tunable number of a run is listed once
// here with its section, unit and meaning; the scenario TOML maps onto it 1:1, `talus params`
// prints it as JSON, and run.json records the resolved values.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

namespace talus::cli {

class ParameterTable {
 public:
  using Target = std::variant<double*, int*, std::uint64_t*, std::string*, bool*>;
  struct Entry {
    std::string section, name, unit, description;
    Target target;
    bool pinned = false;  // given on the command line: a scenario file does not override it
  };

  void add(std::string section, std::string name, std::string unit, std::string description, Target target);
  // {section: {name: value}}: the resolved values, for run.json.
  nlohmann::json values() const;
  // [{section, name, unit, description, default}], for `talus params`.
  nlohmann::json describe() const;
  // Marks an entry as given on the command line, so that the scenario file leaves it alone.
  void pin(const std::string& section, const std::string& name);
  // Sets the values found in a scenario file's sections, except pinned ones; unknown sections or
  // keys, and values of the wrong type, are InputError naming the file and the key.
  void apply_scenario(const std::filesystem::path& scenario, const std::vector<std::string>& ignored_sections);
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  std::vector<Entry> entries_;
};

}  // namespace talus::cli
