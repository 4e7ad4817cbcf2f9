// Blow-up detection for the full model's time steps (issue 4, Deliver 5).
#include "talus/rockfall/step_guard.hpp"

#include <cmath>
#include <cstdio>
#include <string>


namespace talus {

// Issue 4, Deliver 5: a finite state, and no energy created beyond the step's fluctuation.
bool step_is_sound(const RockState& after, const StepEnergy& before, const StepEnergy& after_energy,
                   double tolerance, double floor) {
  const bool finite = after.position.allFinite() && after.velocity.allFinite() &&
                      after.angular_momentum.allFinite() && after.orientation.coeffs().allFinite() &&
                      std::isfinite(after_energy.mechanical());
  if (!finite) return false;
  const double allowed = tolerance * (before.kinetic + before.elastic + floor);
  return after_energy.mechanical() - before.mechanical() <= allowed;
}

void throw_numerical_failure(double time, const Eigen::Vector3d& position, double step, const char* reason) {
  char message[256];
  std::snprintf(message, sizeof message,
                "full rock-fall model: %s at t = %.6g s, centre (%.3f, %.3f, %.3f) m, step %.3g s", reason, time,
                position.x(), position.y(), position.z(), step);
  throw StepFailure(message, time, position, step, reason);
}

}  // namespace talus
