// Names of the reasons a trajectory stops, as written into trajectories.gpkg and run.json, and
// which of the two ways out of the valid ground a rock took.
#include "talus/rockfall/trajectory_observer.hpp"

namespace talus {

const char* to_string(StopReason reason) {
  switch (reason) {
    case StopReason::at_rest: return "at_rest";
    case StopReason::max_time: return "max_time";
    case StopReason::left_dem: return "left_dem";
    case StopReason::nodata_area: return "nodata_area";
    case StopReason::tile_edge: return "tile_edge";
  }
  return "unknown";
}

StopReason reason_for_leaving(const GridSpec& spec, const Eigen::Vector3d& at) {
  const double col = spec.col_of(at.x());
  const double row = spec.row_of(at.y());
  const bool in_extent = col >= 0.0 && col <= spec.width - 1.0 && row >= 0.0 && row <= spec.height - 1.0;
  return in_extent ? StopReason::nodata_area : StopReason::left_dem;
}

}  // namespace talus
