// A rock's shape, size and mass (paper 3.1). Fast mode uses the shape only through its mass,
// inertia and bounding box; the full model (next issue) samples its implicit surface.
// sphere: diameter axes.x() (the other two axes are not used); ellipsoid: full axes;
// box: the superellipsoid |x/a|^8 + |y/b|^8 + |z/c|^8 <= 1 with a, b, c half the axes (a box
// with rounded edges and corners, kBoxExponent below).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "talus/core/block_shape.hpp"

namespace talus {

// Exponent of the superellipsoid that stands for a box (8: 94% of the box's volume).
inline constexpr double kBoxExponent = 8.0;

// The rocks a run accepts, from its options or from a release feature: every axis strictly
// between these (m), a density between these (kg/m3, inclusive).
inline constexpr double kMinRockAxis = 0.01, kMaxRockAxis = 100.0;
inline constexpr double kMinRockDensity = 500.0, kMaxRockDensity = 6000.0;

struct Rock {
  BlockShape shape = BlockShape::sphere;
  Eigen::Vector3d axes = Eigen::Vector3d::Ones();  // full lengths along the local x, y, z axes (m)
  double density = 2700.0;                         // kg/m3

  double volume() const;                           // m3 (box: the superellipsoid's, see rock.cpp)
  double mass() const { return density * volume(); }  // kg
  Eigen::Matrix3d inertia() const;                 // kg m2 about the centre, local frame
  double bounding_radius() const;                  // m: half the largest axis (box corners reach up to 1.51x)
  // Half the vertical extent of the rock's world-aligned bounding box (m): the distance from
  // the centre down to the fast mode's contact point (paper 3.3, "Fast Bounce mode", step 1).
  double half_height(const Eigen::Quaterniond& orientation) const;
  double frontal_area() const;                     // m2: pi r^2 of the equivalent sphere, for drag
};

}  // namespace talus
