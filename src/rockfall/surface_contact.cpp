// The rolling/sliding phase of the fast bounce mode (paper 3.3; friction and vegetation of
// paper 2.1).
#include "talus/rockfall/surface_contact.hpp"

#include <cmath>

namespace talus {

// tan(slope) = sqrt(1 - n_z^2) / n_z <= mu, written without the division (at equality the
// pull of gravity and the friction balance, as in contact_acceleration).
bool friction_holds(const Eigen::Vector3d& normal, double friction) {
  return normal.head<2>().norm() <= friction * normal.z();
}

// Coulomb friction under the normal load g n_z per unit mass (the centripetal part of the load
// on curved ground is neglected) plus the vegetation's quadratic friction (paper 2.1).
Eigen::Vector3d contact_acceleration(const Eigen::Vector3d& velocity, const Eigen::Vector3d& normal,
                                     double friction, double deperdition, double gravity) {
  const Eigen::Vector3d tangential_gravity = -gravity * (Eigen::Vector3d::UnitZ() - normal.z() * normal);
  const double coulomb = friction * gravity * normal.z();
  const double speed = velocity.norm();
  if (speed > 0.0) {
    return tangential_gravity - (coulomb / speed + deperdition * speed) * velocity;
  }
  const double pull = tangential_gravity.norm();
  if (pull <= coulomb) return Eigen::Vector3d::Zero();
  return (1.0 - coulomb / pull) * tangential_gravity;
}

// x = v t + a t^2 / 2, v' = v + a t; the step ends at t* = |v| / (-a.v/|v|) when the speed
// along the motion reaches zero before the end.
SurfaceMove move_on_surface(const Eigen::Vector3d& velocity, const Eigen::Vector3d& acceleration, double duration) {
  SurfaceMove move;
  move.duration = duration;
  const double speed = velocity.norm();
  if (speed > 0.0) {
    const double along = acceleration.dot(velocity) / speed;
    if (along < 0.0 && speed + along * duration <= 0.0) {
      move.duration = -speed / along;
      move.came_to_rest = true;
    }
  }
  const double t = move.duration;
  move.displacement = t * velocity + 0.5 * t * t * acceleration;
  move.velocity = move.came_to_rest ? Eigen::Vector3d::Zero() : Eigen::Vector3d(velocity + t * acceleration);
  return move;
}

}  // namespace talus
