// Tests of the fast bounce impulse (paper 3.3) with the vegetation deperdition (paper 2.1).
#include "talus/rockfall/fast_bounce_impact.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace talus {
namespace {

GroundMaterial material(double rn, double rt, double c = 0.0) {
  GroundMaterial m;
  m.restitution_normal = rn;
  m.restitution_tangential = rt;
  m.vegetation_deperdition = c;
  return m;
}

TEST(FastBounceImpact, ReflectsWithNormalAndTangentialRestitution) {
  const ImpactResponse r = fast_bounce_impact({3.0, 0.0, -4.0}, Eigen::Vector3d::UnitZ(), material(0.5, 0.8), 10.0, 1.0);
  EXPECT_LT((r.velocity - Eigen::Vector3d(2.4, 0.0, 2.0)).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(r.normal_speed, 2.0);
  EXPECT_NEAR(r.deformation_loss, 0.5 * 10.0 * (25.0 - 2.4 * 2.4 - 4.0), 1e-12);
  EXPECT_EQ(r.friction_loss, 0.0);
}

TEST(FastBounceImpact, WorksAboutAnInclinedNormal) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.4, 1.0).normalized();
  const Eigen::Vector3d v(5.0, 2.0, -7.0);
  const ImpactResponse r = fast_bounce_impact(v, n, material(0.35, 0.65), 1.0, 1.0);
  const Eigen::Vector3d v_t = v - v.dot(n) * n;
  EXPECT_NEAR(r.velocity.dot(n), -0.35 * v.dot(n), 1e-12);
  EXPECT_LT(((r.velocity - r.velocity.dot(n) * n) - 0.65 * v_t).norm(), 1e-12);
  EXPECT_NEAR(r.deformation_loss, 0.5 * (v.squaredNorm() - r.velocity.squaredNorm()), 1e-12);
}

TEST(FastBounceImpact, VegetationScalesTheSpeedByExpMinusCD) {
  const double c = 0.05, d = 2.0, mass = 3.0;
  const Eigen::Vector3d v(6.0, 0.0, -8.0);
  const ImpactResponse bare = fast_bounce_impact(v, Eigen::Vector3d::UnitZ(), material(0.5, 0.8), mass, d);
  const ImpactResponse forest = fast_bounce_impact(v, Eigen::Vector3d::UnitZ(), material(0.5, 0.8, c), mass, d);
  EXPECT_LT((forest.velocity - std::exp(-c * d) * bare.velocity).norm(), 1e-12);
  EXPECT_NEAR(forest.normal_speed, std::exp(-c * d) * bare.normal_speed, 1e-12);
  EXPECT_DOUBLE_EQ(forest.deformation_loss, bare.deformation_loss);
  const double kept = 0.5 * mass * bare.velocity.squaredNorm();
  EXPECT_NEAR(forest.friction_loss, kept * (1.0 - std::exp(-2.0 * c * d)), 1e-9);
  // Every joule is accounted for.
  EXPECT_NEAR(0.5 * mass * v.squaredNorm(),
              0.5 * mass * forest.velocity.squaredNorm() + forest.deformation_loss + forest.friction_loss, 1e-9);
}

TEST(FastBounceImpact, ARockMovingAwayKeepsNoNormalVelocity) {
  const ImpactResponse r = fast_bounce_impact({2.0, 0.0, 0.5}, Eigen::Vector3d::UnitZ(), material(0.5, 1.0), 1.0, 1.0);
  EXPECT_EQ(r.normal_speed, 0.0);
  EXPECT_LT((r.velocity - Eigen::Vector3d(2.0, 0.0, 0.0)).norm(), 1e-15);
  EXPECT_NEAR(r.deformation_loss, 0.5 * 0.25, 1e-15);
}

}  // namespace
}  // namespace talus
