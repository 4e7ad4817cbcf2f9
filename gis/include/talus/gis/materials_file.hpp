// Materials tables in TOML (the lithology and vegetation classes of ground/materials.hpp).
// The format is documented in docs/materials.md.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "talus/ground/materials.hpp"

namespace talus::gis {

// One number of a materials class as the file names it, with its unit and the values it may
// take (issue 18, item 1): read_materials refuses any other, `talus params` prints them.
struct MaterialsField {
  std::string_view kind;  // "lithology" or "vegetation"
  std::string_view key, unit, meaning;
  double min, max;
};
const std::vector<MaterialsField>& materials_fields();

// Reads a materials TOML file; throws InputError naming the file and the problem.
MaterialsTable read_materials(const std::filesystem::path& path);
// The same table as TOML text that read_materials reads back unchanged.
std::string materials_to_toml(const MaterialsTable& table);

}  // namespace talus::gis
