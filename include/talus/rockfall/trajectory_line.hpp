// One sampled trajectory kept for trajectories.gpkg (DESIGN.md section 3).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "talus/rockfall/trajectory_observer.hpp"

namespace talus {

struct TrajectoryLine {
  std::uint64_t source_id = 0;             // release cell or point number
  std::uint64_t run_id = 0;                // run of that source
  StopReason stop_reason = StopReason::at_rest;
  double max_energy = 0;                   // kJ, largest kinetic energy on the way
  double runout_length = 0;                // m, horizontal path length from release to stop
  std::vector<Eigen::Vector3d> points;     // centre of mass, CRS x, y and elevation (m)
};

}  // namespace talus
