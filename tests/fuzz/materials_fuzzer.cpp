// Fuzz target: materials TOML files (--materials, docs/materials.md). A table that is read must
// become a ground model on the fixed DEM and must read back unchanged from the text Talus writes
// for it (materials_to_toml, as `talus calibrate` writes it); either failing is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "fuzz_input.hpp"
#include "talus/gis/materials_file.hpp"
#include "talus/gis/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace talus;
  const auto path = fuzz::fuzz_folder().write("materials.toml", data, size);
  std::optional<MaterialsTable> table;
  fuzz::refused_or_read([&] { table = gis::read_materials(path); });
  if (!table) return 0;

  const std::string text = gis::materials_to_toml(*table);
  const std::string again = gis::materials_to_toml(gis::read_materials(fuzz::fuzz_folder().write("written.toml", text)));
  if (again != text) {
    std::fprintf(stderr, "materials_to_toml does not read back unchanged:\n%s\n--- read back as ---\n%s\n", text.c_str(),
                 again.c_str());
    std::abort();
  }
  gis::SceneInputs inputs;
  inputs.dem = fuzz::fixed_dem();
  inputs.materials = path;
  gis::load_scene(inputs).ground_model();
  return 0;
}
