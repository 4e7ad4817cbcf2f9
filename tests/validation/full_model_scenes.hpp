// Rocks, soils and start states shared by the full rock-ground model's tests (paper 2.1 stress
// cycles, paper 3.1 rocks), on the in-memory grounds of synthetic_ground.hpp.
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "synthetic_ground.hpp"
#include "talus/ground/ground_model.hpp"
#include "talus/ground/perturbed_ground.hpp"
#include "talus/rockfall/rigid_body.hpp"
#include "talus/rockfall/rock.hpp"

namespace talus::full_model_scenes {

// The built-in "talus" class's stress cycle (docs/materials.md): k1 1e8, Y 8e5, k2 7e7, k3 1.9e8
// Pa/m, with sliding and rolling friction `friction` (-).
inline GroundMaterial talus_soil(double friction = 0.4, double deperdition = 0.0) {
  GroundMaterial material;
  material.elastic_slope = 1.0e8;
  material.yield_pressure = 8.0e5;
  material.plastic_slope = 7.0e7;
  material.unloading_slope = 1.9e8;
  material.friction = friction;
  material.rolling_friction = friction;
  material.vegetation_deperdition = deperdition;
  return material;
}

// A soil without dissipation: k3 = k1 = k (Pa/m), no yield.
inline GroundMaterial elastic_soil(double stiffness, double friction) {
  GroundMaterial material;
  material.elastic_slope = stiffness;
  material.yield_pressure = std::numeric_limits<double>::infinity();
  material.plastic_slope = stiffness;
  material.unloading_slope = stiffness;
  material.friction = friction;
  material.rolling_friction = friction;
  return material;
}

inline Rock sphere(double diameter) {
  Rock rock;
  rock.axes = Eigen::Vector3d::Constant(diameter);
  return rock;
}

inline Rock block(BlockShape shape, const Eigen::Vector3d& axes) {
  Rock rock;
  rock.shape = shape;
  rock.axes = axes;
  return rock;
}

// width x height cells of `cell` m, a plane falling towards +x by `gradient` (m/m) from z0 (m).
inline GroundModel inclined_plane(int width, int height, double cell, double z0, double gradient,
                                  const GroundMaterial& material) {
  return testing_ground::make_ground(testing_ground::local_spec(width, height, cell),
                                     [z0, gradient](double x, double) { return z0 - gradient * x; }, material);
}

// At rest with the centre `above` m over the ground at (x, y).
inline RigidBodyState released(const PerturbedGround& ground, double x, double y, double above) {
  RigidBodyState start;
  start.position = {x, y, ground.height(x, y) + above};
  return start;
}

}  // namespace talus::full_model_scenes
