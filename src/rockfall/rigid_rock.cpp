// The full model's rock as a rigid body (paper 3.1): implicit parts in the body frame, mass
// properties integrated over the shape, and the two halves of the kick-drift-kick integrator.
#include "talus/rockfall/rigid_rock.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace talus {
namespace {

constexpr double kMaxSubstepAngle = 0.01;  // rad: largest turn of one drift substep

// The rotation by the angle |w| t about w (rad/s, over t seconds) as a unit quaternion: the
// exponential exp(w t / 2) of the pure quaternion (0, w t / 2).
Eigen::Quaterniond rotation_over(const Eigen::Vector3d& w, double duration) {
  const double angle = w.norm() * duration;
  if (angle == 0.0) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w.normalized()));
}

// w = R I^-1 R^T L (rad/s) for the rotation R (body -> world).
Eigen::Vector3d spin(const RigidRock& rock, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& momentum) {
  return rotation * (rock.inverse_inertia() * (rotation.transpose() * momentum));
}

}  // namespace

// Paper 3.1: one part, the rock's implicit shape with its origin moved to the centre of mass
// that integrate_mass finds; mass and inertia from the same integration (uniform density).
RigidRock::RigidRock(const Rock& rock, int surface_samples, int mass_resolution) {
  const ImplicitShape shape(rock, surface_samples);
  const MassProperties properties = integrate_mass(shape, rock.density, mass_resolution);
  if (!(properties.mass > 0.0)) throw std::invalid_argument("RigidRock: the rock has no volume");
  parts_.push_back(RockPart{shape.shifted(properties.centre), Eigen::Vector3d::Zero()});
  mass_ = properties.mass;
  inertia_ = properties.inertia;
  inverse_inertia_ = inertia_.inverse();
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia_, Eigen::EigenvaluesOnly).eigenvalues();
  min_inertia_ = moments.minCoeff();
  anisotropy_ = (moments.maxCoeff() - min_inertia_) / moments.maxCoeff();
  for (const RockPart& part : parts_) {
    bounding_radius_ = std::max(bounding_radius_, part.offset.norm() + part.shape.bounding_radius());
  }
  inner_radius_ = 0.5 * (rock.shape == BlockShape::sphere ? rock.axes.x() : rock.axes.minCoeff());
}

// Paper 3.1 (implicit surface of a body of several parts): the union of the parts, min of their
// functions.
double RigidRock::value(const Eigen::Vector3d& body) const {
  double f = std::numeric_limits<double>::infinity();
  for (const RockPart& part : parts_) f = std::min(f, part.shape.value(body - part.offset));
  return f;
}

Eigen::Vector3d RigidRock::gradient(const Eigen::Vector3d& body) const {
  const RockPart* nearest = &parts_.front();
  double f = std::numeric_limits<double>::infinity();
  for (const RockPart& part : parts_) {
    const double g = part.shape.value(body - part.offset);
    if (g < f) {
      f = g;
      nearest = &part;
    }
  }
  return nearest->shape.gradient(body - nearest->offset);
}

// Paper 2.2 (the carpet covers the rock's axis-parallel bounding box): the union of the parts'
// boxes, each around its offset turned into world axes.
Eigen::AlignedBox3d RigidRock::world_bounds(const Eigen::Quaterniond& orientation) const {
  Eigen::AlignedBox3d box;
  for (const RockPart& part : parts_) {
    Eigen::AlignedBox3d part_box = part.shape.world_bounds(orientation);
    part_box.translate(orientation * part.offset);
    box.extend(part_box);
  }
  return box;
}

// Paper 3.2 over the parts; a part's moment about its own origin moves to the centre by
// (R offset) x F.
Eigen::Vector3d RigidRock::drag(const Eigen::Quaterniond& orientation, const Eigen::Vector3d& velocity,
                                double air_density, double drag_coefficient, Eigen::Vector3d& torque) const {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  torque.setZero();
  for (const RockPart& part : parts_) {
    Eigen::Vector3d part_torque;
    const Eigen::Vector3d part_force =
        surface_drag(part.shape, orientation, velocity, air_density, drag_coefficient, &part_torque);
    force += part_force;
    torque += part_torque + (orientation * part.offset).cross(part_force);
  }
  return force;
}

Eigen::Vector3d angular_velocity(const RigidRock& rock, const RockState& state) {
  return spin(rock, state.orientation.toRotationMatrix(), state.angular_momentum);
}

// Paper 3.1: translation plus rotation, 1/2 m v^2 + 1/2 L . w (J).
double kinetic_energy(const RigidRock& rock, const RockState& state) {
  return 0.5 * rock.mass() * state.velocity.squaredNorm() +
         0.5 * state.angular_momentum.dot(angular_velocity(rock, state));
}

RockState rock_state(const RigidRock& rock, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                     const Eigen::Quaterniond& orientation, const Eigen::Vector3d& angular_velocity) {
  RockState state;
  state.position = position;
  state.velocity = velocity;
  state.orientation = orientation.normalized();
  const Eigen::Matrix3d rotation = state.orientation.toRotationMatrix();
  state.angular_momentum = rotation * (rock.inertia() * (rotation.transpose() * angular_velocity));
  return state;
}

// Paper 3.1, Newton and Euler's laws over a kick: dp = F dt, dL = T dt.
void kick(RockState& state, double mass, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
          double duration) {
  state.velocity += (duration / mass) * force;
  state.angular_momentum += duration * torque;
}

// Paper 3.1, free motion at fixed momenta: x += v dt; q <- exp(w h / 2) q over substeps h with
// w taken at the orientation reached after half the substep (turned by the substep's starting
// spin), second order like the translation. The spin changes during a free rotation only as
// much as the inertia is anisotropic, (I_max - I_min) / I_max; substeps turn the rock by at most
// kMaxSubstepAngle divided by that, so that a long flight step keeps the free rotation's energy
// to about 1e-6 while a sphere turns in one substep (docs/rockfall-full.md, section 2).
void drift(const RigidRock& rock, RockState& state, double duration) {
  state.position += duration * state.velocity;
  const Eigen::Vector3d& momentum = state.angular_momentum;
  if (momentum.isZero(0.0)) return;
  Eigen::Vector3d w = spin(rock, state.orientation.toRotationMatrix(), momentum);
  const double turn = w.norm() * duration * rock.anisotropy();
  const int substeps = std::max(1, static_cast<int>(std::ceil(turn / kMaxSubstepAngle)));
  const double h = duration / substeps;
  for (int k = 0; k < substeps; ++k) {
    const Eigen::Quaterniond halfway = (rotation_over(w, 0.5 * h) * state.orientation).normalized();
    const Eigen::Vector3d w_middle = spin(rock, halfway.toRotationMatrix(), momentum);
    state.orientation = (rotation_over(w_middle, h) * state.orientation).normalized();
    if (k + 1 < substeps) w = spin(rock, state.orientation.toRotationMatrix(), momentum);
  }
}

}  // namespace talus
