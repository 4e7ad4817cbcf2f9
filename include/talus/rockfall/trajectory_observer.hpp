// What a trajectory reports while it runs: the seam between the trajectory models (fast bounce,
// the piston carpet) and everything downstream (hazard statistics, sampled trajectory lines). A
// model calls on_sample at least every `sample_spacing` metres of travel and at every contact, so
// consecutive samples are joined by straight segments; a rock that breaks (paper fig. 4) reports
// its fragments one after the other, each begun by on_fragment.
#pragma once

#include <cstddef>

#include <Eigen/Core>

#include "talus/core/grid_spec.hpp"

namespace talus {

enum class StopReason {
  at_rest,        // speed fell below the stop threshold where friction holds the rock
  max_time,       // the simulated time limit was reached
  left_dem,       // the rock left the DEM's extent
  nodata_area,    // the rock entered cells without elevation
  tile_edge,      // the rock reached the edge of its tile's halo (a tiled run, docs/study.md "Tiles")
};
inline constexpr std::size_t kStopReasonCount = 5;
const char* to_string(StopReason reason);

// Why a rock at `at` (m), where the ground is not defined, stops: left_dem outside the DEM's node
// lattice, nodata_area inside it (cells without elevation).
StopReason reason_for_leaving(const GridSpec& spec, const Eigen::Vector3d& at);

struct TrajectorySample {
  double time = 0;                                      // s since release
  Eigen::Vector3d position = Eigen::Vector3d::Zero();   // centre of mass (m)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();   // m/s
  double kinetic_energy = 0;                            // J, translation + rotation
  double jump_height = 0;                               // m, centre above the (perturbed) ground
};

class TrajectoryObserver {
 public:
  virtual ~TrajectoryObserver() = default;
  virtual void on_sample(const TrajectorySample& sample) = 0;
  // Energy dissipated at (x, y) since the last call (J): by friction (sliding, rolling,
  // vegetation) and by ground deformation (impacts).
  virtual void on_energy_loss(double x, double y, double friction, double deformation) = 0;
  virtual void on_stop(const TrajectorySample& last, StopReason reason) = 0;
  // Paper fig. 4: the rock broke. The samples after this call belong to a new fragment starting
  // at `start` (its first sample, not reported again through on_sample), not joined to the
  // previous sample; every fragment ends with its own on_stop. A trajectory reports its first
  // fragment (the rock from its release on, continued at each break by the piece that holds the
  // block's first part) to its on_stop, then each other fragment from its on_fragment to its
  // on_stop. Observers that follow one rock only can ignore it (the default does nothing).
  virtual void on_fragment([[maybe_unused]] const TrajectorySample& start) {}
  // The model restarted the rock from its last sound state after a step failed at `time` (s)
  // (full mode, docs/rockfall-full.md, section 5, "Recovery"). What it had computed since that
  // state was never reported, so the reports stay one consistent trajectory; this call only
  // says that it happened (the default does nothing).
  virtual void on_restart([[maybe_unused]] double time) {}
};

}  // namespace talus
