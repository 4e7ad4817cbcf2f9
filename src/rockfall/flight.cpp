// Flight between contacts (paper 3.1, 3.2): exact parabola without drag, RK4 with it.
#include "talus/rockfall/flight.hpp"

#include <cmath>

namespace talus {

Flight::Flight(double gravity, const AirDrag& drag, double mass)
    : gravity_(gravity),
      drag_per_mass_(drag.per_mass(mass)),
      terminal_speed_(drag_per_mass_ > 0.0 ? std::sqrt(gravity / drag_per_mass_) : 0.0) {}

// Paper 3.2: gravity plus the drag force over the mass, -k |v| v.
Eigen::Vector3d Flight::acceleration(const Eigen::Vector3d& velocity) const {
  Eigen::Vector3d a = (-drag_per_mass_ * velocity.norm()) * velocity;
  a.z() -= gravity_;
  return a;
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

FlightArc::FlightArc(const PointState& start, const PointState& end, double duration)
    : start_(start), end_(end), duration_(duration) {}

// Cubic Hermite basis on s = tau / duration: p(s) = h00 p0 + h10 T v0 + h01 p1 + h11 T v1 with
// h00 = 2s^3 - 3s^2 + 1, h10 = s^3 - 2s^2 + s, h01 = -2s^3 + 3s^2, h11 = s^3 - s^2, and its
// derivative over T for the velocity.
PointState FlightArc::at(double tau) const {
  if (duration_ <= 0.0) return start_;
  const double s = tau / duration_;
  const double s2 = s * s;
  const double T = duration_;
  const Eigen::Vector3d velocity = ((6.0 * s2 - 6.0 * s) / T) * (start_.position - end_.position) +
                                   (3.0 * s2 - 4.0 * s + 1.0) * start_.velocity + (3.0 * s2 - 2.0 * s) * end_.velocity;
  return {position(tau), velocity};
}

// The position part of at(): what the ground-crossing searches need at each trial time.
Eigen::Vector3d FlightArc::position(double tau) const {
  if (duration_ <= 0.0) return start_.position;
  const double s = tau / duration_;
  const double s2 = s * s, s3 = s2 * s;
  const double T = duration_;
  return (2.0 * s3 - 3.0 * s2 + 1.0) * start_.position + (T * (s3 - 2.0 * s2 + s)) * start_.velocity +
         (3.0 * s2 - 2.0 * s3) * end_.position + (T * (s3 - s2)) * end_.velocity;
}

}  // namespace talus
