// Names of the reasons a trajectory stops, as written into trajectories.gpkg and run.json.
#include "talus/rockfall/trajectory_observer.hpp"

namespace talus {

const char* to_string(StopReason reason) {
  switch (reason) {
    case StopReason::at_rest: return "at_rest";
    case StopReason::max_time: return "max_time";
    case StopReason::left_dem: return "left_dem";
    case StopReason::nodata_area: return "nodata_area";
  }
  return "unknown";
}

}  // namespace talus
