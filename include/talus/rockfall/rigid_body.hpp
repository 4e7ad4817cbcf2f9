// Rigid-body state of a rock (paper 3.1: "animated with usual dynamic laws of motion").
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace talus {

struct RigidBodyState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();          // centre of mass (m), x east, y north, z up
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // m/s
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // local -> world
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s, world frame
};

}  // namespace talus
