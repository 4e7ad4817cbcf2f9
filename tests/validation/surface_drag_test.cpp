// Air friction as the surface integral of paper 3.2 over the rock's samples, against closed
// forms (docs/references.md, "Rock fall"): over a sphere it is the quadratic drag of air_drag.hpp in
// every direction, a falling sphere reaches the terminal velocity sqrt(2 m g / (rho Cx pi r^2))
// (issue 4: within 1%), an ellipsoid falls faster along its long axis in the ratio of its
// frontal areas, and centrally symmetric rocks feel no drag torque.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "talus/rockfall/air_drag.hpp"
#include "talus/rockfall/implicit_shape.hpp"

namespace talus {
namespace {

constexpr double kG = 9.81;            // m/s2
constexpr double kAirDensity = 1.225;  // kg/m3
constexpr double kCx = 0.1;            // paper 3.2, heavy sphere

Rock make_rock(BlockShape shape, const Eigen::Vector3d& axes, double density) {
  Rock rock;
  rock.shape = shape;
  rock.axes = axes;
  rock.density = density;
  return rock;
}

Eigen::Quaterniond random_orientation(std::mt19937& random) {
  std::normal_distribution<double> normal;
  return Eigen::Quaterniond(Eigen::Vector4d(normal(random), normal(random), normal(random), normal(random))).normalized();
}

// Vertical fall from rest at a fixed orientation, m dv/dt = m g + F_drag(v), by classical
// Runge-Kutta with steps of `step` seconds for `duration` seconds; returns the final speed (m/s).
double fall_speed(const ImplicitShape& shape, double mass, const Eigen::Quaterniond& orientation, double duration,
                  double step) {
  const Eigen::Vector3d gravity(0.0, 0.0, -kG);
  const auto acceleration = [&](const Eigen::Vector3d& v) -> Eigen::Vector3d {
    return gravity + surface_drag(shape, orientation, v, kAirDensity, kCx) / mass;
  };
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  const int steps = static_cast<int>(std::round(duration / step));
  for (int i = 0; i < steps; ++i) {
    const Eigen::Vector3d k1 = acceleration(v);
    const Eigen::Vector3d k2 = acceleration(v + 0.5 * step * k1);
    const Eigen::Vector3d k3 = acceleration(v + 0.5 * step * k2);
    const Eigen::Vector3d k4 = acceleration(v + step * k3);
    v += step / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return v.norm();
}

TEST(SurfaceDrag, SphereMatchesTheClosedFormInEveryDirection) {
  const double r = 0.5;  // m
  const ImplicitShape sphere(make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(2.0 * r), 2700.0));
  const AirDrag closed_form{kAirDensity, kCx, std::numbers::pi * r * r};
  std::mt19937 random(17);
  std::normal_distribution<double> normal(0.0, 10.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d v(normal(random), normal(random), normal(random));
    const Eigen::Vector3d expected = closed_form.force(v);
    const Eigen::Vector3d force = surface_drag(sphere, random_orientation(random), v, kAirDensity, kCx);
    // Within 1% of -1/2 rho Cx pi r^2 |v| v at 256 samples (measured at most 0.25%), along -v.
    EXPECT_LT((force - expected).norm(), 1e-2 * expected.norm());
    EXPECT_NEAR(force.normalized().dot(v.normalized()), -1.0, 1e-12);
  }
  Eigen::Vector3d torque = Eigen::Vector3d::Ones();
  EXPECT_EQ(surface_drag(sphere, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero(), kAirDensity, kCx, &torque),
            Eigen::Vector3d::Zero());
  EXPECT_EQ(torque, Eigen::Vector3d::Zero());
}

TEST(SurfaceDrag, TerminalVelocityOfASphereMatchesTheClosedForm) {
  // A light sphere (0.2 m, 50 kg/m3) reaches v_t = sqrt(2 m g / (rho Cx pi r^2)) = 32.7 m/s
  // with a time constant v_t / g = 3.3 s; 40 s of fall leave it 1e-10 short. Tilted so that the
  // flow meets the samples in a generic direction. Within 1% (issue 4; measured 0.03%).
  const double r = 0.1;  // m
  const Rock rock = make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(2.0 * r), 50.0);
  const ImplicitShape sphere(rock);
  const double terminal = std::sqrt(2.0 * rock.mass() * kG / (kAirDensity * kCx * std::numbers::pi * r * r));
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 0.5).normalized()));
  const double speed = fall_speed(sphere, rock.mass(), tilt, 40.0, 0.01);
  EXPECT_NEAR(speed / terminal, 1.0, 1e-2);
}

TEST(SurfaceDrag, EllipsoidFallsFasterAlongItsLongAxis) {
  // Semi-axes (a, b, c) = (0.2, 0.14, 0.08) m: falling along x it shows the frontal area pi b c,
  // along z pi a b, so the terminal speeds differ by sqrt(a / c) = 1.58; within 1% (measured 0.01%).
  const Rock rock = make_rock(BlockShape::ellipsoid, Eigen::Vector3d(0.4, 0.28, 0.16), 50.0);
  const ImplicitShape ellipsoid(rock);
  const Eigen::Quaterniond long_axis_down(Eigen::AngleAxisd(0.5 * std::numbers::pi, Eigen::Vector3d::UnitY()));
  const double along_long = fall_speed(ellipsoid, rock.mass(), long_axis_down, 40.0, 0.01);
  const double along_short = fall_speed(ellipsoid, rock.mass(), Eigen::Quaterniond::Identity(), 40.0, 0.01);
  EXPECT_GT(along_long, along_short);
  EXPECT_NEAR(along_long / along_short / std::sqrt(0.2 / 0.08), 1.0, 1e-2);
  // And it equals sqrt(2 m g / (rho Cx A)) with its frontal area, within 1% (measured 0.003%).
  const double frontal_long = std::numbers::pi * 0.14 * 0.08;
  EXPECT_NEAR(along_long / std::sqrt(2.0 * rock.mass() * kG / (kAirDensity * kCx * frontal_long)), 1.0, 1e-2);
}

TEST(SurfaceDrag, TorqueVanishesOnSymmetricRocksAndIsTheSumOfSampleMoments) {
  // The drag acts at the centroid of the rock's shadow (the facing samples weighted by their
  // projected areas): on the centre for a sphere or a tilted ellipsoid (central symmetry), so
  // |torque| <= 1% of |F| times the bounding radius (measured at most 0.3%).
  std::mt19937 random(23);
  const ImplicitShape sphere(make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(1.0), 2700.0));
  const ImplicitShape ellipsoid(make_rock(BlockShape::ellipsoid, Eigen::Vector3d(2.0, 1.4, 0.8), 2700.0));
  for (const ImplicitShape* shape : {&sphere, &ellipsoid}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Vector3d v(3.0 * trial - 20.0, 5.0, -12.0);
      Eigen::Vector3d torque;
      const Eigen::Vector3d force = surface_drag(*shape, random_orientation(random), v, kAirDensity, kCx, &torque);
      EXPECT_LT(torque.norm(), 1e-2 * force.norm() * shape->bounding_radius());
    }
  }
  // A half ellipsoid about its centroid: the torque is the sum of r x dF over the facing
  // samples (to rounding, 1e-12 relative) and does not vanish in an oblique flow (measured 2%
  // of |F| times the bounding radius).
  const ImplicitShape half = ellipsoid.cut({Eigen::Vector3d(0.3, 0.0, 1.0).normalized(), 0.0});
  const MassProperties properties = integrate_mass(half, 2700.0, 32);
  const ImplicitShape part = half.shifted(properties.centre);
  const Eigen::Quaterniond q = random_orientation(random);
  const Eigen::Vector3d v(4.0, -7.0, -15.0);
  Eigen::Vector3d torque;
  const Eigen::Vector3d force = surface_drag(part, q, v, kAirDensity, kCx, &torque);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const SurfaceSample& sample : part.surface()) {
    const Eigen::Vector3d n = q * sample.normal;
    if (n.dot(v) <= 0.0) continue;
    const Eigen::Vector3d df = -0.5 * kAirDensity * kCx * v.norm() * v * n.dot(v.normalized()) * sample.area;
    sum += (q * sample.position).cross(df);
  }
  EXPECT_LT((torque - sum).norm(), 1e-12 * sum.norm());
  EXPECT_GT(torque.norm(), 1e-2 * force.norm() * part.bounding_radius());
}

}  // namespace
}  // namespace talus
