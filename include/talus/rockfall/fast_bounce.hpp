// Fast bounce mode (paper 3.3, "Fast Bounce mode"): flight under gravity and air drag, one
// contact point at the bottom of the rock's bounding box, an impulse that reflects the
// velocity about the ground normal with normal and tangential restitution, vegetation energy
// deperdition, and a rolling phase with rolling resistance (Azzoni et al. 1995) so that rocks
// come to rest. Equations, choices and every parameter: docs/rockfall-fast.md. Samples: at
// release, before and after every impact (same time and place), at every take-off, at least
// every sample_spacing metres, and the final state, which on_stop receives too. Energies count
// translation and rotation: the spin is the rolling value n x v_t / r of the last contact.
#pragma once

#include "talus/rockfall/trajectory_model.hpp"

namespace talus {

struct FastBounceParameters {
  double gravity = 9.81;              // m/s2
  double air_density = 1.225;         // kg/m3
  double drag_coefficient = 0.1;      // Cx (-), paper 3.2: 0.1 for a heavy sphere; 0 disables drag
  double max_time = 300.0;            // s of simulated time
  double stop_speed = 0.1;            // m/s: below it, a rock in contact where friction holds stops
  double contact_speed = 0.5;         // m/s: a touchdown or rebound slower than this along the
                                      // ground normal leaves the rock in contact
  double max_step_length = 1.0;       // m: longest path between two ground checks in flight
  double sample_spacing = 2.5;        // m: longest path between two reported samples
  double contact_time_step = 0.25;    // s: longest step of the rolling/sliding phase (each step is
                                      // exact on a plane; steps also stay within max_step_length)
  double contact_tolerance = 0.03;    // m: in contact, a drop of the ground this far below the
                                      // free-flight path makes the rock take off; a rise this far
                                      // above its path ends the step there (a new contact)
};

class FastBounce final : public TrajectoryModel {
 public:
  explicit FastBounce(FastBounceParameters parameters = {}) : parameters_(parameters) {}
  StopReason run(const PerturbedGround& ground, const Rock& rock, RigidBodyState start,
                 TrajectoryObserver& observer) const override;
  const FastBounceParameters& parameters() const { return parameters_; }

 private:
  FastBounceParameters parameters_;
};

}  // namespace talus
