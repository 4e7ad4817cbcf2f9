// What a release feature's conditions (core/release_conditions.hpp, issue 16) make of a run:
// the nominal rock of its sources and the velocity they start with.
#pragma once

#include <Eigen/Core>

#include "talus/core/release_conditions.hpp"
#include "talus/rockfall/rock.hpp"

namespace talus {

// The run's rock with the shape, axes and density the conditions give (the others kept).
Rock release_rock(const Rock& run_rock, const ReleaseConditions& conditions);

// The start velocity of the rock's centre (m/s, x east, y north, z up): at rest when none is given.
Eigen::Vector3d release_velocity(const ReleaseConditions& conditions);

}  // namespace talus
