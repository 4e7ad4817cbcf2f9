// Fuzz target: the raster inputs of a scene (docs/inputs.md), through load_scene as every command
// reads them: the input as the DEM (with its own CRS, and with --crs local) and its ground model,
// then as the lithology, and as the vegetation and erodible rasters, of the fixed DEM. GDAL
// finds the format from the content: GeoTIFF, ASCII grid, VRT and every other raster driver.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "fuzz_input.hpp"
#include "talus/gis/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace talus;
  const auto input = fuzz::gdal_input("raster", data, size);
  if (!input) return 0;
  const std::filesystem::path& path = *input;
  const std::filesystem::path& dem = fuzz::fixed_dem();

  for (const char* crs : {"", "local"}) {
    gis::SceneInputs inputs;
    inputs.dem = path;
    inputs.crs = crs;
    fuzz::refused_or_read([&] { gis::load_scene(inputs).ground_model(); });
  }
  gis::SceneInputs lithology;
  lithology.dem = dem;
  lithology.lithology = path;
  fuzz::refused_or_read([&] { gis::load_scene(lithology).ground_model(); });
  gis::SceneInputs vegetation;
  vegetation.dem = dem;
  vegetation.vegetation = path;
  vegetation.erodible = path;
  fuzz::refused_or_read([&] { gis::load_scene(vegetation).ground_model(); });
  return 0;
}
