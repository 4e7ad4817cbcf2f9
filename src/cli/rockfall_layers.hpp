// The hazard layers a rock-fall run writes (docs/architecture.md section 3), with their file names,
// descriptions and units: written by `talus rockfall`, and the names its intensity classes may use.
#pragma once

#include "intensity_layer.hpp"
#include "talus/rockfall/rockfall_statistics.hpp"

namespace talus::cli {

// The layers of `layers` (names only are read from an empty RockfallLayers{}).
HazardLayers rockfall_hazard_layers(const RockfallLayers& layers);

}  // namespace talus::cli
