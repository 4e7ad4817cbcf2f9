// Hazard guidelines' intensity classes (docs/hazard-statistics.md, "Intensity classes"): read
// from src/cli/intensity_guidelines.toml, built into the program, or from a user's TOML file in
// the same format, into the IntensityScheme of one process.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "talus/hazard/hazard_matrix.hpp"
#include "talus/hazard/intensity_classes.hpp"

namespace talus::cli {

// The scheme `choice` names for `process` ("rockfall" or "mudflow"): a guideline of the built-in
// file, or FILE.toml (its `default` guideline, or its only one). Throws InputError naming the
// file or option and the problem.
IntensityScheme intensity_scheme(const std::string& choice, const std::string& process);

// The hazard matrix of the guideline `choice` names (as intensity_scheme()), none when it has
// no [NAME.hazard] table. Throws InputError naming the file and the problem.
std::optional<HazardMatrix> hazard_matrix(const std::string& choice);

// "foen-2016, ...": the built-in guidelines, for messages and `talus params`.
nlohmann::json built_in_intensity_guidelines();

}  // namespace talus::cli
