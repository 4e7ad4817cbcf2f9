// Tests of the air drag of paper 3.2 integrated over a sphere.
#include "talus/rockfall/air_drag.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace talus {
namespace {

TEST(AirDrag, OpposesTheVelocityWithHalfRhoCxAVSquared) {
  const AirDrag drag{1.2, 0.4, 0.5};
  const Eigen::Vector3d v(3.0, -4.0, 12.0);  // |v| = 13
  const Eigen::Vector3d force = drag.force(v);
  EXPECT_NEAR(force.norm(), 0.5 * 1.2 * 0.4 * 0.5 * 169.0, 1e-12);
  EXPECT_NEAR(force.normalized().dot(v.normalized()), -1.0, 1e-15);
  EXPECT_EQ(drag.force(Eigen::Vector3d::Zero()), Eigen::Vector3d::Zero());
}

TEST(AirDrag, PerMassCoefficientGivesTheDeceleration) {
  const AirDrag drag{1.225, 0.1, 0.785};
  const double mass = 1414.0;
  const Eigen::Vector3d v(20.0, 5.0, -10.0);
  const Eigen::Vector3d expected = -drag.per_mass(mass) * v.norm() * v;
  EXPECT_LT((drag.force(v) / mass - expected).norm(), 1e-15);
  // Terminal velocity sqrt(g / k) = sqrt(2 m g / (rho Cx A)).
  EXPECT_NEAR(std::sqrt(9.81 / drag.per_mass(mass)), std::sqrt(2.0 * mass * 9.81 / (1.225 * 0.1 * 0.785)), 1e-9);
}

}  // namespace
}  // namespace talus
