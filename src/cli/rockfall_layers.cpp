// The hazard layers of a rock-fall run (rockfall_layers.hpp).
#include "rockfall_layers.hpp"

namespace talus::cli {

// The ten layers of docs/architecture.md section 3 with their band descriptions and units.
HazardLayers rockfall_hazard_layers(const RockfallLayers& layers) {
  return {{&layers.reach_probability, {"reach_probability", "Reach probability per contributing source", ""}},
          {&layers.passages, {"passages", "Number of passages", ""}},
          {&layers.source_count, {"source_count", "Number of release sources reaching the cell", ""}},
          {&layers.deposits, {"deposits", "Number of deposited rocks", ""}},
          {&layers.energy_max, {"energy_max", "Maximum kinetic energy", "kJ"}},
          {&layers.energy_p95, {"energy_p95", "95th percentile of kinetic energy over passages", "kJ"}},
          {&layers.jump_height_p95, {"jump_height_p95", "95th percentile of jump height over passages", "m"}},
          {&layers.velocity_max, {"velocity_max", "Maximum velocity", "m/s"}},
          {&layers.energy_loss_friction,
           {"energy_loss_friction", "Energy lost by friction, mean per simulated rock", "kJ"}},
          {&layers.energy_loss_deformation,
           {"energy_loss_deformation", "Energy lost by ground deformation, mean per simulated rock", "kJ"}}};
}

}  // namespace talus::cli
