#include "study_units.hpp"

#include <fstream>
#include <stdexcept>

#include "talus/gis/run_record.hpp"

namespace talus::cli {
namespace {

std::filesystem::path unit_path(const std::filesystem::path& out, const StudyScenario& s) {
  return out / ".units" / (s.name + ".json");
}

}  // namespace

nlohmann::ordered_json unit_record(const StudyScenario& s, nlohmann::ordered_json parameters,
                                   const std::vector<std::filesystem::path>& inputs, FileChecksums& checksums) {
  if (parameters.contains("run")) parameters["run"].erase("threads");
  nlohmann::ordered_json files = nlohmann::ordered_json::object();
  for (const std::filesystem::path& input : inputs) {
    if (input.empty()) continue;
    const std::filesystem::path absolute = std::filesystem::absolute(input);
    auto known = checksums.find(absolute);
    if (known == checksums.end()) known = checksums.emplace(absolute, gis::sha256_of_file(input)).first;
    files[absolute.string()] = known->second;
  }
  nlohmann::ordered_json record = {{"talus_version", TALUS_VERSION},
                                   {"process", to_string(s.process)},
                                   {"parameters", parameters},
                                   {"inputs", files}};
  if (s.detect_sources) {
    record["sources"] = {{"source_slope", s.source_slope ? nlohmann::ordered_json(*s.source_slope) : nullptr},
                         {"source_lithology", s.source_lithology}};
  }
  return record;
}

bool unit_done(const std::filesystem::path& out, const StudyScenario& s, const nlohmann::ordered_json& record) {
  std::error_code ec;
  if (!std::filesystem::exists(out / "scenarios" / s.name / "run.json", ec)) return false;
  std::ifstream file(unit_path(out, s));
  if (!file) return false;
  try {
    return nlohmann::ordered_json::parse(file) == record;
  } catch (const nlohmann::json::exception&) {
    return false;  // a record cut short: the unit runs again
  }
}

void mark_unit_done(const std::filesystem::path& out, const StudyScenario& s, const nlohmann::ordered_json& record) {
  const std::filesystem::path path = unit_path(out, s);
  std::filesystem::create_directories(path.parent_path());
  const std::filesystem::path partial = path.string() + ".partial";
  {
    std::ofstream file(partial);
    file << record.dump(2) << '\n';
    if (!file) throw std::runtime_error("cannot write " + partial.string());
  }
  std::filesystem::rename(partial, path);
  // The scenario is whole: its units of work are not needed any more.
  std::filesystem::remove_all(unit_parts_folder(out, s));
}

std::filesystem::path unit_parts_folder(const std::filesystem::path& out, const StudyScenario& s) {
  return out / ".units" / (s.name + ".parts");
}

}  // namespace talus::cli
