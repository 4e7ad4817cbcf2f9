// Tests of the mass properties integrated over the implicit surface (paper 3.1): volume, mass,
// centre of mass and inertia tensor of the sphere, the ellipsoid and the box against rock.hpp's
// closed forms, and of cut parts (paper fig. 4) against the hemisphere's.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "talus/rockfall/implicit_shape.hpp"

namespace talus {
namespace {

Rock make_rock(BlockShape shape, const Eigen::Vector3d& axes, double density = 2700.0) {
  Rock rock;
  rock.shape = shape;
  rock.axes = axes;
  rock.density = density;
  return rock;
}

// Largest off-diagonal term relative to the trace (-).
double off_diagonal(const Eigen::Matrix3d& inertia) {
  return std::max({std::abs(inertia(0, 1)), std::abs(inertia(0, 2)), std::abs(inertia(1, 2))}) / inertia.trace();
}

TEST(MassProperties, SphereVolume) {
  const Rock rock = make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(1.0));
  const MassProperties properties = integrate_mass(ImplicitShape(rock), rock.density);
  // Volume, mass and inertia within 0.5% (measured 0.05% and 0.03%); centre at the origin
  // within 1e-4 m.
  EXPECT_NEAR(properties.volume / rock.volume(), 1.0, 5e-3);
  EXPECT_NEAR(properties.mass / rock.mass(), 1.0, 5e-3);
  EXPECT_LT(properties.centre.norm(), 1e-4);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(properties.inertia(i, i) / rock.inertia()(i, i), 1.0, 5e-3);
}

TEST(MassProperties, EllipsoidInertiaMatchesTheClosedForm) {
  // Axes (2, 1.4, 0.8) m: I_x = m (b^2 + c^2) / 5 and cyclic, each within 0.5% (issue 4;
  // measured 0.03% to 0.10%), the volume within 0.5% (measured 0.05%).
  const Rock rock = make_rock(BlockShape::ellipsoid, Eigen::Vector3d(2.0, 1.4, 0.8));
  const MassProperties properties = integrate_mass(ImplicitShape(rock), rock.density);
  EXPECT_NEAR(properties.volume / rock.volume(), 1.0, 5e-3);
  EXPECT_NEAR(properties.mass / rock.mass(), 1.0, 5e-3);
  const Eigen::Matrix3d expected = rock.inertia();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(properties.inertia(i, i) / expected(i, i), 1.0, 5e-3) << i;
  // Symmetric body: centre at the origin (1e-4 m), principal axes along the local ones (1e-4).
  EXPECT_LT(properties.centre.norm(), 1e-4);
  EXPECT_LT(off_diagonal(properties.inertia), 1e-4);
  EXPECT_TRUE(properties.inertia.isApprox(properties.inertia.transpose(), 1e-14));
}

TEST(MassProperties, BoxInertiaMatchesTheSuperellipsoidClosedForm) {
  // Rock::inertia() of the exponent-8 superellipsoid (Dirichlet's integral), within 0.5%
  // (measured 0.01%).
  const Rock rock = make_rock(BlockShape::box, Eigen::Vector3d(2.0, 1.4, 0.8), 2500.0);
  const MassProperties properties = integrate_mass(ImplicitShape(rock), rock.density);
  EXPECT_NEAR(properties.mass / rock.mass(), 1.0, 5e-3);
  const Eigen::Matrix3d expected = rock.inertia();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(properties.inertia(i, i) / expected(i, i), 1.0, 5e-3) << i;
  EXPECT_LT(off_diagonal(properties.inertia), 1e-4);
}

TEST(MassProperties, HemispheresAddUpToTheSphere) {
  const double r = 0.5;  // m
  const Rock rock = make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(2.0 * r));
  const ImplicitShape sphere(rock);
  const ImplicitShape lower = sphere.cut({Eigen::Vector3d::UnitZ(), 0.0});
  const ImplicitShape upper = sphere.cut({-Eigen::Vector3d::UnitZ(), 0.0});
  const MassProperties below = integrate_mass(lower, rock.density);
  const MassProperties above = integrate_mass(upper, rock.density);
  // The halves' masses sum to the whole within 0.5% (measured 0.04%).
  EXPECT_NEAR((below.mass + above.mass) / rock.mass(), 1.0, 5e-3);
  // Centre of mass 3 r / 8 from the cut plane within 1% (measured 0.02%), on the axis (1e-4 m).
  EXPECT_NEAR(below.centre.z() / (-3.0 * r / 8.0), 1.0, 1e-2);
  EXPECT_NEAR(above.centre.z() / (3.0 * r / 8.0), 1.0, 1e-2);
  EXPECT_LT(below.centre.head<2>().norm(), 1e-4);
  // Inertia about the centre of mass: 2/5 m r^2 about the axis, (2/5 - 9/64) m r^2 across it,
  // within 0.5% (measured 0.01%).
  const double m = below.mass;
  EXPECT_NEAR(below.inertia(2, 2) / (0.4 * m * r * r), 1.0, 5e-3);
  EXPECT_NEAR(below.inertia(0, 0) / ((0.4 - 9.0 / 64.0) * m * r * r), 1.0, 5e-3);
  EXPECT_NEAR(below.inertia(1, 1) / ((0.4 - 9.0 / 64.0) * m * r * r), 1.0, 5e-3);
}

TEST(MassProperties, ShiftingToTheCentreKeepsTheTensor) {
  // A part re-centred on its centre of mass (paper 3.1: the rigid body's frame): centre at the
  // new origin (1e-4 m) and the same mass and tensor about it (0.1%; measured 1e-12, the grid
  // moves with the origin).
  const Rock rock = make_rock(BlockShape::box, Eigen::Vector3d(2.0, 1.4, 0.8));
  const ImplicitShape part = ImplicitShape(rock).cut({Eigen::Vector3d(1.0, 0.5, 0.2).normalized(), 0.1});
  const MassProperties off_centre = integrate_mass(part, rock.density);
  const MassProperties centred = integrate_mass(part.shifted(off_centre.centre), rock.density);
  EXPECT_LT(centred.centre.norm(), 1e-4);
  EXPECT_NEAR(centred.mass / off_centre.mass, 1.0, 1e-3);
  EXPECT_LT((centred.inertia - off_centre.inertia).norm(), 1e-3 * off_centre.inertia.norm());
}

TEST(MassProperties, ConvergesWithResolution) {
  // Second-order surface treatment: the ellipsoid's volume error at 32 cells per axis is at
  // least twice that at 64 (measured 4x), both below 1%.
  const Rock rock = make_rock(BlockShape::ellipsoid, Eigen::Vector3d(2.0, 1.4, 0.8));
  const ImplicitShape shape(rock);
  const double coarse = std::abs(integrate_mass(shape, 1.0, 32).volume / rock.volume() - 1.0);
  const double fine = std::abs(integrate_mass(shape, 1.0, 64).volume / rock.volume() - 1.0);
  EXPECT_LT(coarse, 1e-2);
  EXPECT_LT(2.0 * fine, coarse);
  EXPECT_THROW(integrate_mass(shape, 1.0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace talus
