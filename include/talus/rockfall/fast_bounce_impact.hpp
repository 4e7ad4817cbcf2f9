// The fast bounce impulse (paper 3.3, "Fast Bounce mode", step 2): the velocity is reflected
// about the ground normal with energy-loss coefficients, here the lithology's normal and
// tangential restitutions, and then slowed by the vegetation (paper 2.1, last paragraph).
#pragma once

#include <Eigen/Core>

#include "talus/ground/ground_model.hpp"

namespace talus {

struct ImpactResponse {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s after the impact
  double normal_speed = 0;       // m/s: velocity . normal after the impact (>= 0)
  double deformation_loss = 0;   // J: kinetic energy taken by the restitutions
  double friction_loss = 0;      // J: kinetic energy taken by the vegetation
};

// velocity: before the impact (m/s); normal: unit upward ground normal; mass (kg);
// contact_length (m): the distance over which the vegetation acts (the rock's diameter).
// v' = exp(-c d) (-Rn min(v.n, 0) n + Rt v_t), v_t = v - (v.n) n: a rock already moving away
// from the ground (v.n >= 0) keeps no normal velocity.
ImpactResponse fast_bounce_impact(const Eigen::Vector3d& velocity, const Eigen::Vector3d& normal,
                                  const GroundMaterial& material, double mass, double contact_length);

}  // namespace talus
