// Materials tables in TOML (the lithology and vegetation classes of ground/materials.hpp).
// The format is documented in docs/materials.md.
#pragma once

#include <filesystem>
#include <string>

#include "talus/ground/materials.hpp"

namespace talus::gis {

// Reads a materials TOML file; throws InputError naming the file and the problem.
MaterialsTable read_materials(const std::filesystem::path& path);
// The same table as TOML text that read_materials reads back unchanged.
std::string materials_to_toml(const MaterialsTable& table);

}  // namespace talus::gis
