// Fuzz target: --release on the fixed DEM (docs/inputs.md, "Release"): a raster of depths or a
// vector layer (GeoJSON, GeoPackage, GML, KML and every other OGR driver that finds the format
// from the content), read through load_scene as `talus rockfall` reads it (with the rock-fall
// attributes, then its release sources) and as `talus mudflow` does (every depth required).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "talus/gis/scene.hpp"
#include "talus/rockfall/monte_carlo.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace talus;
  const auto input = fuzz::gdal_input("release", data, size);
  if (!input) return 0;

  gis::SceneInputs rockfall;
  rockfall.dem = fuzz::fixed_dem();
  rockfall.release = *input;
  rockfall.run_rock = RockfallSettings{}.rock;
  fuzz::refused_or_read([&] { release_sources(*gis::load_scene(rockfall).release); });
  gis::SceneInputs mudflow;
  mudflow.dem = fuzz::fixed_dem();
  mudflow.release = *input;
  mudflow.release_needs_depth = true;
  fuzz::refused_or_read([&] { gis::load_scene(mudflow); });
  return 0;
}
