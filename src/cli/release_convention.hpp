// How a mud-flow release's depths are read, and the volume that gives (issue 37, item 4;
// docs/inputs.md, "How a mud-flow depth is measured"): said by `talus info`, printed by
// `talus mudflow` and recorded in its run.json, so that nobody has to guess which of the two
// volumes a run released.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "talus/core/release.hpp"
#include "talus/ground/ground_model.hpp"
#include "talus/mudflow/release_particles.hpp"

namespace talus::cli {

struct ReleaseConvention {
  ReleaseThicknessChoice choice = ReleaseThicknessChoice::automatic;  // [mud] release_thickness
  ReleaseThickness thickness = ReleaseThickness::normal;              // what the choice gives for this release
  double volume = 0;        // m3 with `thickness`
  double other_volume = 0;  // m3 with the other convention
};

ReleaseConvention release_convention(const GroundModel& ground, const ReleaseSet& release,
                                     ReleaseThicknessChoice choice);

// "depths read as thickness normal to the ground (auto: ...): 17325 m3; as vertical depths 14445 m3"
std::string release_convention_text(const ReleaseConvention& convention);

// {"depth_measured": ..., "release_thickness": ..., "reason": ..., "volume_m3": {"normal", "vertical"}}
nlohmann::ordered_json release_convention_record(const ReleaseConvention& convention);

}  // namespace talus::cli
