// One sampled trajectory kept for trajectories.gpkg (docs/architecture.md section 3; issue 17, item 6): its
// line, and at each vertex what a profile plot needs.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "talus/core/release.hpp"
#include "talus/rockfall/trajectory_observer.hpp"

namespace talus {

struct TrajectoryVertex {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // centre of mass, CRS x, y and elevation (m)
  double time = 0;                                     // s since release
  double speed = 0;                                    // m/s
  double kinetic_energy = 0;                           // kJ, translation + rotation
  double jump_height = 0;                              // m, centre above the (perturbed) ground
};

// Vertices closer than this (m) to the previous one are not kept: a line has no zero-length
// segment (a rock at rest reports its last place again).
inline constexpr double kShortestTrajectorySegment = 1e-6;

struct TrajectoryLine {
  std::uint64_t source_id = 0;             // release cell or point number (0-based, as --only-source)
  std::uint64_t run_id = 0;                // run of that source
  std::int64_t release_fid = kNoReleaseFeature;  // FID of the release feature of the source
  StopReason stop_reason = StopReason::at_rest;
  double max_energy = 0;                   // kJ, largest kinetic energy on the way
  double runout_length = 0;                // m, horizontal path length from release to stop
  std::vector<TrajectoryVertex> vertices;  // in time order, no two within kShortestTrajectorySegment
};

}  // namespace talus
