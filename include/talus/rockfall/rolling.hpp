// A rigid rock rolling on the ground, for the fast bounce mode (paper 3.3's contact phase, with
// rolling resistance after Azzoni et al. 1995, docs/references.md, "Rock fall"): the share A of the
// kinetic energy a rolling rock carries in translation, its rolling spin, and the change from
// a bounce to rolling. Equations: docs/rockfall-fast.md, section 5.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace talus {

// What rolling needs of a rock at its current orientation.
struct RollingBody {
  double mass = 0;                                           // kg
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();         // kg m2 about the centre, world axes
  double radius = 0;                                         // m: centre's height above the contact point
};

// Azzoni's A = m / (m + I_e / r^2) for rolling along `direction` on ground of unit normal
// `normal`, I_e the inertia about the rolling axis normal x direction (5/7 for a sphere). A
// rolling rock's kinetic energy is 1/2 m |v|^2 / A. Without a direction (zero), the largest
// inertia about an axis in the ground's plane is used.
double rolling_share(const RollingBody& body, const Eigen::Vector3d& normal, const Eigen::Vector3d& direction);

// The spin of rolling without slip at the centre's velocity v, the centre `radius` m above the
// contact point: normal x v / radius (rad/s). Inline, as rotation_energy: fast mode asks for both
// at every contact step and sample.
inline Eigen::Vector3d rolling_spin(double radius, const Eigen::Vector3d& normal, const Eigen::Vector3d& velocity) {
  return normal.cross(velocity) / radius;
}

// 1/2 w . I w (J).
inline double rotation_energy(const RollingBody& body, const Eigen::Vector3d& spin) {
  return 0.5 * spin.dot(body.inertia * spin);
}

// A rigid rock rolling down ground of slope tan t needs the friction force (1 - A) m g sin t +
// A mu_r m g cos t at its contact point (Newton and Euler with Azzoni's resisting torque mu_r N r);
// it rolls without slip where the sliding friction mu can give it: (1 - A) tan t + A mu_r <= mu.
inline bool rolls_without_slip(double share, double slope_tangent, double sliding_friction, double rolling_friction) {
  return (1.0 - share) * slope_tangent + share * rolling_friction <= sliding_friction;
}

// A rock that touches down with the tangential velocity `velocity` and the spin `spin` starts to
// roll: friction at the contact point conserves the angular momentum about it along the rolling
// axis, m r v + I_e w_e = (m r + I_e / r) u, so the rolling speed is u = A v + (1 - A) r w_e
// (5/7 v for a sphere without spin), never negative and never with more kinetic energy than the
// rock brought. Returns the centre's velocity after.
Eigen::Vector3d start_rolling(const RollingBody& body, const Eigen::Vector3d& normal, const Eigen::Vector3d& velocity,
                              const Eigen::Vector3d& spin);

}  // namespace talus
