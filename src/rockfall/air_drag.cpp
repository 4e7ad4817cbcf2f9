// Air friction during flight (paper 3.2), integrated over a sphere.
#include "talus/rockfall/air_drag.hpp"

namespace talus {

// Paper 3.2: 1/2 rho Cx |V| V integrated over the sphere's front, i.e. times pi r^2.
Eigen::Vector3d AirDrag::force(const Eigen::Vector3d& velocity) const {
  return -0.5 * air_density * drag_coefficient * frontal_area * velocity.norm() * velocity;
}

// Paper 3.2 divided by the mass: the coefficient of the drag deceleration -k |v| v.
double AirDrag::per_mass(double mass) const { return 0.5 * air_density * drag_coefficient * frontal_area / mass; }

}  // namespace talus
