// Flight between contacts (paper 3.1, 3.2): exact parabola without drag, RK4 with it.
#include "talus/rockfall/flight.hpp"

#include <cmath>
#include <limits>

namespace talus {

Flight::Flight(double gravity, const AirDrag& drag, double mass)
    : gravity_(gravity),
      drag_(drag),
      inverse_mass_(1.0 / mass),
      drag_per_mass_(drag.per_mass(mass)),
      terminal_speed_(drag_per_mass_ > 0.0 ? std::sqrt(gravity / drag_per_mass_) : 0.0) {}

// Paper 3.2: gravity plus the drag force over the mass.
Eigen::Vector3d Flight::acceleration(const Eigen::Vector3d& velocity) const {
  return Eigen::Vector3d(0.0, 0.0, -gravity_) + inverse_mass_ * drag_.force(velocity);
}

// Without drag, x(t) = x0 + v0 t + g t^2 / 2 exactly (the projectile's closed form). With drag,
// one classical RK4 step of dx/dt = v, dv/dt = g - k |v| v.
PointState Flight::advance(const PointState& start, double duration) const {
  const double h = duration;
  if (!has_drag()) {
    const Eigen::Vector3d g(0.0, 0.0, -gravity_);
    return {start.position + h * start.velocity + 0.5 * h * h * g, start.velocity + h * g};
  }
  const Eigen::Vector3d& v1 = start.velocity;
  const Eigen::Vector3d a1 = acceleration(v1);
  const Eigen::Vector3d v2 = v1 + 0.5 * h * a1;
  const Eigen::Vector3d a2 = acceleration(v2);
  const Eigen::Vector3d v3 = v1 + 0.5 * h * a2;
  const Eigen::Vector3d a3 = acceleration(v3);
  const Eigen::Vector3d v4 = v1 + h * a3;
  const Eigen::Vector3d a4 = acceleration(v4);
  return {start.position + h / 6.0 * (v1 + 2.0 * v2 + 2.0 * v3 + v4),
          start.velocity + h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4)};
}

// Paper 3.2: |g - k |v| v| <= g + k |v|^2, the bound the step lengths use.
double Flight::acceleration_bound(const Eigen::Vector3d& velocity) const {
  return gravity_ + drag_per_mass_ * velocity.squaredNorm();
}

// The drag's time scale is 1 / (k |v|), and v_terminal / g = 1 / (k v_terminal) at low speed:
// two hundredths of it keep RK4's local error (order 5) far below the tests' 1e-6.
double Flight::max_duration(const Eigen::Vector3d& velocity) const {
  if (!has_drag()) return std::numeric_limits<double>::infinity();
  return 0.02 / (drag_per_mass_ * (velocity.norm() + terminal_speed_));
}

// Positive root of (a / 2) t^2 + speed t - length = 0, written without cancellation.
double duration_for_length(double speed, double acceleration, double length) {
  return 2.0 * length / (speed + std::sqrt(speed * speed + 2.0 * acceleration * length));
}

}  // namespace talus
