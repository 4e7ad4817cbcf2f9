// The hazard layers of a mud-flow run (mudflow_layers.hpp).
#include "mudflow_layers.hpp"

namespace talus::cli {

// The mud-flow layers of docs/architecture.md section 3 with their band descriptions and units; erosion_depth
// only when the run has erodible material.
HazardLayers mudflow_hazard_layers(const FlowLayers& layers) {
  HazardLayers out = {
      {&layers.flow_depth_max, {"flow_depth_max", "Maximum flow depth", "m"}},
      {&layers.velocity_max, {"velocity_max", "Maximum velocity", "m/s"}},
      {&layers.pressure_max, {"pressure_max", "Maximum impact pressure", "kPa"}},
      {&layers.deposit_depth, {"deposit_depth", "Deposit depth", "m"}},
      {&layers.arrival_time,
       {"arrival_time", "Arrival time of the flow", "s", gis::OverviewReduction::earliest_positive}}};
  if (layers.erosion_depth) out.push_back({&*layers.erosion_depth, {"erosion_depth", "Eroded depth", "m"}});
  return out;
}

}  // namespace talus::cli
