// A TOML file a user gives (a scenario, a study, an intensity guideline), read with the one-line
// errors of issue 18: "NAME: file not found", "NAME: line N: what the parser says".
#pragma once

#include <filesystem>
#include <string>

#include <toml++/toml.h>

namespace talus::cli {

// `name` says how messages name the file, e.g. "flow.toml (scenario)"; throws InputError.
toml::table read_toml_file(const std::filesystem::path& path, const std::string& name);

}  // namespace talus::cli
