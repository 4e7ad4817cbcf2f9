// Flight between contacts (paper 3.1 "usual dynamic laws of motion", 3.2 air friction): the
// centre of mass under gravity and the sphere's air drag. Without drag the step is the exact
// parabola, so its length does not matter; with drag it is one classical fourth-order
// Runge-Kutta step, kept short by max_duration() so that its error stays below 1e-7 relative.
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "talus/rockfall/air_drag.hpp"

namespace talus {

struct PointState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // m
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s
};

class Flight {
 public:
  // gravity: g (m/s2, pointing down -z); drag: the rock's air drag; mass (kg).
  Flight(double gravity, const AirDrag& drag, double mass);

  // The state `duration` seconds after `start`.
  PointState advance(const PointState& start, double duration) const;
  // Upper bound of the acceleration's magnitude at this velocity (m/s2): g + k |v|^2, since
  // |g - k |v| v| <= g + k |v|^2 (paper 3.2).
  double acceleration_bound(const Eigen::Vector3d& velocity) const {
    return gravity_ + drag_per_mass_ * velocity.squaredNorm();
  }
  // Longest RK4 step (s) at this velocity: 0.02 / (k (|v| + v_terminal)); infinite without drag.
  // The drag's time scale is 1 / (k |v|), and v_terminal / g = 1 / (k v_terminal) at low speed:
  // two hundredths of it keep RK4's local error (order 5) far below the tests' 1e-6.
  double max_duration(const Eigen::Vector3d& velocity) const {
    if (!has_drag()) return std::numeric_limits<double>::infinity();
    return 0.02 / (drag_per_mass_ * (velocity.norm() + terminal_speed_));
  }
  bool has_drag() const { return drag_per_mass_ > 0.0; }

 private:
  Eigen::Vector3d acceleration(const Eigen::Vector3d& velocity) const;
  double gravity_;
  double drag_per_mass_;     // k (1/m)
  double terminal_speed_;    // sqrt(g / k) (m/s)
};

// One flight step as a curve in time, for locating ground crossings inside it without
// re-integrating: the cubic Hermite interpolant of the positions and velocities at the step's
// two ends (the step's dense output). It reproduces the drag-free parabola exactly; with drag
// its error is of order duration^4 times the drag's rate of change of acceleration.
class FlightArc {
 public:
  FlightArc(const PointState& start, const PointState& end, double duration);
  PointState at(double tau) const;  // state tau seconds after the start, 0 <= tau <= duration
  Eigen::Vector3d position(double tau) const;  // at(tau).position, without the velocity

 private:
  PointState start_, end_;
  double duration_;
};

// Longest time (s) in which a point starting at `speed` (m/s) with an acceleration of magnitude at
// most `acceleration` (m/s2) moves at most `length` (m): the root of speed t + a t^2 / 2 = length,
// written without cancellation.
inline double duration_for_length(double speed, double acceleration, double length) {
  return 2.0 * length / (speed + std::sqrt(speed * speed + 2.0 * acceleration * length));
}

}  // namespace talus
