// A rigid rock rolling on the ground (Azzoni et al. 1995), for the fast bounce mode.
#include "talus/rockfall/rolling.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace talus {
namespace {

// Unit rolling axis for motion along `direction` on ground of unit normal `normal`; zero when
// the direction has no part in the ground's plane.
Eigen::Vector3d rolling_axis(const Eigen::Vector3d& normal, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d axis = normal.cross(direction);
  const double length = axis.norm();
  return length > 0.0 ? Eigen::Vector3d(axis / length) : Eigen::Vector3d::Zero();
}

}  // namespace

// Azzoni et al. 1995: A = m r^2 / (m r^2 + I_e).
double rolling_share(const RollingBody& body, const Eigen::Vector3d& normal, const Eigen::Vector3d& direction) {
  const double m_r2 = body.mass * body.radius * body.radius;
  Eigen::Vector3d axis = rolling_axis(normal, direction);
  double inertia = 0.0;
  if (axis.isZero(0.0)) {
    // No direction: the larger of the inertias about two axes across the normal.
    const Eigen::Vector3d first = rolling_axis(normal, std::abs(normal.x()) < 0.9 ? Eigen::Vector3d::UnitX()
                                                                                  : Eigen::Vector3d::UnitY());
    const Eigen::Vector3d second = normal.cross(first);
    inertia = std::max(first.dot(body.inertia * first), second.dot(body.inertia * second));
  } else {
    inertia = axis.dot(body.inertia * axis);
  }
  return m_r2 / (m_r2 + inertia);
}

// Angular momentum about the contact point along the rolling axis e, before and after:
// m r v + I_e w_e = (m r + I_e / r) u, so u = A v + (1 - A) r w_e with A = m r^2 / (m r^2 + I_e).
// The spin's other components are lost to friction. The speed is capped so that the rolling rock's
// energy 1/2 m u^2 / A never exceeds what it brought (translation plus rotation), which the
// world inertia's coupling of axes could otherwise allow.
Eigen::Vector3d start_rolling(const RollingBody& body, const Eigen::Vector3d& normal, const Eigen::Vector3d& velocity,
                              const Eigen::Vector3d& spin) {
  const double speed = velocity.norm();
  if (speed == 0.0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d direction = velocity / speed;
  const Eigen::Vector3d axis = rolling_axis(normal, direction);
  const double share = rolling_share(body, normal, direction);
  const double rolling = std::max(0.0, share * speed + (1.0 - share) * body.radius * spin.dot(axis));
  const double brought = 0.5 * body.mass * speed * speed + rotation_energy(body, spin);
  const double kept = 0.5 * body.mass * rolling * rolling / share;
  const double capped = kept > brought ? rolling * std::sqrt(brought / kept) : rolling;
  return capped * direction;
}

}  // namespace talus
