// Air friction during flight (paper 3.2): F = 1/2 rho Cx integral of |V| V.n dS over the
// surface seen by the air flow. Over a sphere of radius r the integral of V.n / |V| dS is the
// frontal area A = pi r^2, so F = -1/2 rho Cx A |v| v, opposing the rock's velocity v. Fast mode
// uses it for every shape with the frontal area of the sphere of the same volume.
#pragma once

#include <Eigen/Core>

namespace talus {

struct AirDrag {
  double air_density = 1.225;      // rho (kg/m3)
  double drag_coefficient = 0.1;   // Cx (-), paper 3.2: 0.1 for a heavy sphere
  double frontal_area = 0.0;       // A (m2)

  // Paper 3.2 over a sphere: -1/2 rho Cx A |v| v (N) for the velocity v (m/s). Inline: flight
  // evaluates it four times per Runge-Kutta step.
  Eigen::Vector3d force(const Eigen::Vector3d& velocity) const {
    return -0.5 * air_density * drag_coefficient * frontal_area * velocity.norm() * velocity;
  }
  // k = rho Cx A / (2 m) (1/m): the drag deceleration of a rock of mass m (kg) is -k |v| v.
  double per_mass(double mass) const;
};

}  // namespace talus
