// Tests of the rolling/sliding phase's pieces (paper 3.3 fast mode; friction and vegetation of
// paper 2.1): the friction test, the acceleration in the tangent plane and the exact step.
#include "talus/rockfall/surface_contact.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace talus {
namespace {

constexpr double kG = 9.81;

// Unit normal of a plane rising towards -x at `slope` radians (the fall line is +x).
Eigen::Vector3d plane_normal(double slope) { return {std::sin(slope), 0.0, std::cos(slope)}; }
Eigen::Vector3d fall_line(double slope) { return {std::cos(slope), 0.0, -std::sin(slope)}; }

TEST(SurfaceContact, FrictionHoldsWhereTanSlopeIsBelowMu) {
  const double slope = std::atan(0.5);
  EXPECT_TRUE(friction_holds(plane_normal(slope), 0.6));
  EXPECT_FALSE(friction_holds(plane_normal(slope), 0.4));
  EXPECT_TRUE(friction_holds(Eigen::Vector3d::UnitZ(), 0.0));
}

TEST(SurfaceContact, AccelerationDownTheFallLine) {
  const double slope = 30.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d n = plane_normal(slope);
  const double mu = 0.3;
  const Eigen::Vector3d v = 5.0 * fall_line(slope);
  const Eigen::Vector3d a = contact_acceleration(v, n, mu, 0.0, kG);
  EXPECT_NEAR(a.dot(n), 0.0, 1e-12);
  EXPECT_LT((a - kG * (std::sin(slope) - mu * std::cos(slope)) * fall_line(slope)).norm(), 1e-12);
  // Vegetation adds -c |v| v.
  const Eigen::Vector3d a_veg = contact_acceleration(v, n, mu, 0.02, kG);
  EXPECT_LT((a_veg - a + 0.02 * 5.0 * v).norm(), 1e-12);
  // Moving up the slope, gravity and friction both decelerate.
  const Eigen::Vector3d up = contact_acceleration(-v, n, mu, 0.0, kG);
  EXPECT_NEAR(up.dot(fall_line(slope)), kG * (std::sin(slope) + mu * std::cos(slope)), 1e-12);
}

TEST(SurfaceContact, AtRestEitherHoldsOrStartsDownTheFallLine) {
  const double slope = 30.0 * std::numbers::pi / 180.0;
  EXPECT_EQ(contact_acceleration(Eigen::Vector3d::Zero(), plane_normal(slope), 0.7, 0.0, kG), Eigen::Vector3d::Zero());
  const Eigen::Vector3d a = contact_acceleration(Eigen::Vector3d::Zero(), plane_normal(slope), 0.3, 0.0, kG);
  EXPECT_LT((a - kG * (std::sin(slope) - 0.3 * std::cos(slope)) * fall_line(slope)).norm(), 1e-12);
}

TEST(SurfaceContact, StepIsExactForConstantAcceleration) {
  const Eigen::Vector3d v(3.0, 1.0, 0.0), a(0.5, -0.2, 0.0);
  const SurfaceMove move = move_on_surface(v, a, 0.4);
  EXPECT_FALSE(move.came_to_rest);
  EXPECT_DOUBLE_EQ(move.duration, 0.4);
  EXPECT_LT((move.displacement - (0.4 * v + 0.08 * a)).norm(), 1e-15);
  EXPECT_LT((move.velocity - (v + 0.4 * a)).norm(), 1e-15);
}

TEST(SurfaceContact, StepEndsWhereTheSpeedReachesZero) {
  const Eigen::Vector3d v(4.0, 0.0, 0.0), a(-2.0, 0.0, 0.0);
  const SurfaceMove move = move_on_surface(v, a, 10.0);
  EXPECT_TRUE(move.came_to_rest);
  EXPECT_DOUBLE_EQ(move.duration, 2.0);
  EXPECT_NEAR(move.displacement.x(), 16.0 / 4.0, 1e-12);  // v^2 / (2 |a|)
  EXPECT_EQ(move.velocity, Eigen::Vector3d::Zero());
  EXPECT_FALSE(move_on_surface(v, a, 1.9).came_to_rest);
}

}  // namespace
}  // namespace talus
