// The fast bounce impulse of paper 3.3 with the vegetation deperdition of paper 2.1.
#include "talus/rockfall/fast_bounce_impact.hpp"

#include <algorithm>
#include <cmath>

namespace talus {

// Paper 3.3, "Fast Bounce mode", step 2: reflection about the ground surface, normal part
// scaled by Rn, tangential part by Rt. Paper 2.1: the vegetation's friction force c |v| v per
// unit mass, applied over the contact length d, scales the speed by exp(-c d) (du/ds = -c u).
ImpactResponse fast_bounce_impact(const Eigen::Vector3d& velocity, const Eigen::Vector3d& normal,
                                  const GroundMaterial& material, double mass, double contact_length) {
  const double v_normal = velocity.dot(normal);
  const Eigen::Vector3d v_tangent = velocity - v_normal * normal;
  const double rebound = material.restitution_normal * std::max(-v_normal, 0.0);
  const Eigen::Vector3d restituted = rebound * normal + material.restitution_tangential * v_tangent;
  const double vegetation = std::exp(-material.vegetation_deperdition * contact_length);

  const double energy_before = 0.5 * mass * velocity.squaredNorm();
  const double energy_restituted = 0.5 * mass * restituted.squaredNorm();
  ImpactResponse response;
  response.velocity = vegetation * restituted;
  response.normal_speed = vegetation * rebound;
  response.deformation_loss = energy_before - energy_restituted;
  response.friction_loss = energy_restituted * (1.0 - vegetation * vegetation);
  return response;
}

}  // namespace talus
