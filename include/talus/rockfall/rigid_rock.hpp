// The rock of the full model as a rigid body (paper 3.1): "rigid solids defined by an implicit
// surface whose sample points are stored in a local frame ... provided with a mass and an
// inertia tensor, and animated with usual dynamic laws of motion". The body frame has its
// origin at the centre of mass and the rock's local axes. A body is a list of rigid parts (an
// implicit shape each, placed in the body frame) so that a pre-fractured block (paper fig. 4)
// can later be made of several; today every rock has one part. The state carries the angular
// momentum in the world frame; the integrator's two halves are kick() and drift().
// Equations: docs/rockfall-full.md, section 2.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "talus/rockfall/implicit_shape.hpp"
#include "talus/rockfall/rock.hpp"

namespace talus {

// One rigid part: its implicit shape, whose local origin sits at `offset` in the body frame
// (body point p is the shape's local point p - offset; the axes are shared).
struct RockPart {
  ImplicitShape shape;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // m, body frame
};

class RigidRock {
 public:
  // Paper 3.1: the rock's implicit shape (surface_samples samples) moved to its centre of mass;
  // mass and inertia integrated over it (integrate_mass at mass_resolution, Rock::density).
  RigidRock(const Rock& rock, int surface_samples, int mass_resolution);

  double mass() const { return mass_; }                                       // kg
  const Eigen::Matrix3d& inertia() const { return inertia_; }                 // kg m2, body frame, about the centre
  const Eigen::Matrix3d& inverse_inertia() const { return inverse_inertia_; } // 1/(kg m2)
  double min_inertia() const { return min_inertia_; }                         // kg m2: smallest principal moment
  double anisotropy() const { return anisotropy_; }                           // (I_max - I_min) / I_max (-)
  double bounding_radius() const { return bounding_radius_; }                 // m: the rock lies within it
  // The rock's smallest semi-axis (m). Each part's function is a gauge of a convex body that
  // holds a ball of this radius, so it changes by at most 1 / inner_radius per metre: a point
  // where value() = f > 0 lies at least f x inner_radius outside the rock.
  double inner_radius() const { return inner_radius_; }
  const std::vector<RockPart>& parts() const { return parts_; }

  // The body's implicit function at a body-frame point (m): the smallest over the parts (-),
  // negative inside; and the gradient (1/m, body frame) of the part that gives it.
  double value(const Eigen::Vector3d& body) const;
  Eigen::Vector3d gradient(const Eigen::Vector3d& body) const;

  // World-axis-aligned box around the body at this orientation, relative to the centre (m).
  Eigen::AlignedBox3d world_bounds(const Eigen::Quaterniond& orientation) const;
  // Air friction of paper 3.2 over every part's surface (N, world), and its moment about the
  // centre in `torque` (N m, world).
  Eigen::Vector3d drag(const Eigen::Quaterniond& orientation, const Eigen::Vector3d& velocity, double air_density,
                       double drag_coefficient, Eigen::Vector3d& torque) const;

 private:
  std::vector<RockPart> parts_;
  double mass_ = 0, min_inertia_ = 0, anisotropy_ = 0, bounding_radius_ = 0, inner_radius_ = 0;
  Eigen::Matrix3d inertia_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d inverse_inertia_ = Eigen::Matrix3d::Zero();
};

// The body's state (paper 3.1): centre of mass, its velocity, orientation (body -> world) and
// angular momentum about the centre, both vectors in world axes.
struct RockState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();          // m
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // m/s
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d angular_momentum = Eigen::Vector3d::Zero();  // kg m2/s
};

// w = R I^-1 R^T L (rad/s, world) at the state's orientation.
Eigen::Vector3d angular_velocity(const RigidRock& rock, const RockState& state);
// 1/2 m |v|^2 + 1/2 L . w (J).
double kinetic_energy(const RigidRock& rock, const RockState& state);
// The state of a rock released from a rigid-body state (spin w gives L = R I R^T w).
RockState rock_state(const RigidRock& rock, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                     const Eigen::Quaterniond& orientation, const Eigen::Vector3d& angular_velocity);

// Kick: the momenta change by a force (N) and a torque (N m) acting for `duration` seconds.
void kick(RockState& state, double mass, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
          double duration);
// Drift (paper 3.1, free motion at fixed momenta over `duration` seconds): x += v dt, and the
// orientation turns by exp(w dt / 2) q with the spin w at the step's middle orientation.
void drift(const RigidRock& rock, RockState& state, double duration);

}  // namespace talus
