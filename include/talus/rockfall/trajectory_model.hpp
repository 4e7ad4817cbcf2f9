// The contact-model seam (issue 3): one rock from release to rest on one perturbed ground.
// FastBounce implements it now; the piston-carpet model of paper 2.2/3.3 plugs in the same way.
#pragma once

#include "talus/ground/perturbed_ground.hpp"
#include "talus/rockfall/rigid_body.hpp"
#include "talus/rockfall/rock.hpp"
#include "talus/rockfall/trajectory_observer.hpp"

namespace talus {

class TrajectoryModel {
 public:
  virtual ~TrajectoryModel() = default;
  // Runs until the rock stops; reports samples, losses and the stop to the observer.
  virtual StopReason run(const PerturbedGround& ground, const Rock& rock, RigidBodyState start,
                         TrajectoryObserver& observer) const = 0;
};

}  // namespace talus
