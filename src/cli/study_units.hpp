// Resuming a study (issue 19, item 5; docs/study.md, "Resume"): each scenario is committed whole
// by its layer set; once committed, DIR/.units/NAME.json records what it was computed from (a
// rock fall's smaller units of work are committed inside it as they finish, unit_parts.hpp). A rerun of the same study skips each unit whose record matches what it would
// compute now, and the layers stay bit for bit those of an uninterrupted run, because a scenario's
// layers depend only on what the record holds.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study_file.hpp"

namespace talus::cli {

// What a scenario's layers depend on: the Talus version, the resolved parameters without the
// thread count (the layers do not depend on it), and the SHA-256 of every input file; for sources
// found from the slope, the DEM's and lithology's checksums with the source keys stand for the
// release.
// `checksums` keeps each file's SHA-256 once computed, so the region's DEM is read once a study.
using FileChecksums = std::map<std::filesystem::path, std::string>;
nlohmann::ordered_json unit_record(const StudyScenario& s, nlohmann::ordered_json parameters,
                                   const std::vector<std::filesystem::path>& inputs, FileChecksums& checksums);

// True when OUT/scenarios/NAME holds a committed set and OUT/.units/NAME.json equals `record`.
bool unit_done(const std::filesystem::path& out, const StudyScenario& s, const nlohmann::ordered_json& record);

// Writes OUT/.units/NAME.json (under a temporary name, renamed) after the scenario's set is
// committed, and removes the scenario's units of work.
void mark_unit_done(const std::filesystem::path& out, const StudyScenario& s, const nlohmann::ordered_json& record);

// Within a rock-fall scenario, its units of work (a tile's chunk of sources, unit_parts.hpp) are
// committed here as they finish, so that a killed study resumes inside the scenario too.
std::filesystem::path unit_parts_folder(const std::filesystem::path& out, const StudyScenario& s);

}  // namespace talus::cli
