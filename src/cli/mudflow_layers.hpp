// The hazard layers a mud-flow run writes (docs/architecture.md section 3), with their file names,
// descriptions and units: written by `talus mudflow`, and the names its intensity classes may use.
#pragma once

#include "intensity_layer.hpp"
#include "talus/mudflow/flow_maps.hpp"

namespace talus::cli {

// The layers of `layers`, erosion_depth only when the run has erodible material (names only are
// read from an empty FlowLayers{}).
HazardLayers mudflow_hazard_layers(const FlowLayers& layers);

}  // namespace talus::cli
