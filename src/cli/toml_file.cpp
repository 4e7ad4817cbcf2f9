#include "toml_file.hpp"

#include "talus/core/errors.hpp"

namespace talus::cli {

toml::table read_toml_file(const std::filesystem::path& path, const std::string& name) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(name + ": file not found");
  try {
    return toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    throw InputError(name + ": line " + std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
  }
}

}  // namespace talus::cli
