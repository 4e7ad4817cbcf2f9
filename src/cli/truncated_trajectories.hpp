// The problems a rock-fall run reports about trajectories cut short (issue 17, item 5): rocks
// stopped by the edge of the DEM's valid area (nodata cells), by the edge of the DEM, by the
// simulated time limit, or by the edge of a tile's halo (issue 19, item 4), whose paths the layers
// do not follow to their end.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace talus::cli {

// One problem line per cause that stopped at least one rock, in the form of the scene's
// problems ("trajectories: N of M rocks (S %) ..."). stop_counts: by StopReason, every fragment's
// stop counted (RockfallResult::stop_counts); max_time_key and max_time_s: the time limit's
// parameter as `talus params` names it ("[fast_bounce] max_time") and its value; halo_m: the
// tiles' halo ([tiles] halo).
std::vector<std::string> truncated_trajectory_problems(const std::vector<std::uint64_t>& stop_counts,
                                                       const std::string& max_time_key, double max_time_s,
                                                       double halo_m);

}  // namespace talus::cli
