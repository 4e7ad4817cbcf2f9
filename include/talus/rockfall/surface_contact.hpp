// The rolling/sliding phase of the fast bounce mode (paper 3.3: a fast mode in which rocks come
// to rest): a rock in contact moves in the ground's tangent plane under tangential gravity,
// Coulomb friction mu g n_z against its motion (mu from the lithology table, paper 2.1) and the
// vegetation's friction c |v| v (paper 2.1, last paragraph), all per unit mass.
#pragma once

#include <Eigen/Core>

namespace talus {

// True where the slope of the plane with unit upward normal n is not steeper than the friction
// angle, tan(slope) <= mu: a rock at rest there stays at rest.
bool friction_holds(const Eigen::Vector3d& normal, double friction);

// Acceleration (m/s2) in the tangent plane of normal n at velocity v (in that plane):
// g_t - mu g n_z v/|v| - c |v| v, g_t = -g (z - n_z n). At rest: zero where friction holds,
// else (|g_t| - mu g n_z) along the fall line.
Eigen::Vector3d contact_acceleration(const Eigen::Vector3d& velocity, const Eigen::Vector3d& normal,
                                     double friction, double deperdition, double gravity);

struct SurfaceMove {
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  // m
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      // m/s at the end
  double duration = 0;                                     // s, <= the requested duration
  bool came_to_rest = false;                               // the speed reached zero in the step
};

// Exact motion under the constant acceleration a for `duration` seconds, except that when the
// speed along the motion would reach zero inside the step, the move ends there at rest.
// On a plane this makes the stopping distance exactly v^2 / (2 g (mu cos t - sin t)).
SurfaceMove move_on_surface(const Eigen::Vector3d& velocity, const Eigen::Vector3d& acceleration, double duration);

}  // namespace talus
