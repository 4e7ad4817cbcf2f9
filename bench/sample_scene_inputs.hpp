// The sample scene's inputs (sample_dem/: DEM, lithology, vegetation, cliff release points), as
// every rock-fall benchmark reads them. TALUS_SAMPLE_DIR comes from bench/CMakeLists.txt.
#pragma once

#include <filesystem>

#include "talus/gis/scene.hpp"

inline talus::gis::SceneInputs sample_scene_inputs() {
  const std::filesystem::path dir = TALUS_SAMPLE_DIR;
  talus::gis::SceneInputs inputs;
  inputs.dem = dir / "dem.tif";
  inputs.lithology = dir / "lithology.tif";
  inputs.vegetation = dir / "vegetation.tif";
  inputs.release = dir / "rockfall_release.gpkg";
  return inputs;
}
