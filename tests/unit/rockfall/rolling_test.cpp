// Rolling of a rigid rock (rolling.hpp; Azzoni et al. 1995, docs/rockfall-fast.md, section 5):
// Azzoni's A, the rolling spin, and the start of rolling by friction at the contact point.
#include "talus/rockfall/rolling.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "talus/rockfall/rock.hpp"

namespace talus {
namespace {

RollingBody body_of(const Rock& rock, const Eigen::Quaterniond& orientation, double radius) {
  const Eigen::Matrix3d rotation = orientation.toRotationMatrix();
  return {rock.mass(), rotation * rock.inertia() * rotation.transpose(), radius};
}

Rock ellipsoid(double a, double b, double c) {
  Rock rock;
  rock.shape = BlockShape::ellipsoid;
  rock.axes = {a, b, c};
  return rock;
}

// A = m r^2 / (m r^2 + I_e): 5/7 for a sphere in any direction; for an ellipsoid the inertia
// about the rolling axis n x direction, I_x = m (b^2 + c^2) / 5 for a roll about its x axis.
TEST(Rolling, ShareIsFiveSeventhsForASphereAndFollowsTheRollingAxis) {
  Rock sphere;
  sphere.axes = Eigen::Vector3d::Constant(0.8);
  const RollingBody ball = body_of(sphere, Eigen::Quaterniond::Identity(), 0.4);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  for (const Eigen::Vector3d& direction : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0.6, -0.8, 0), Eigen::Vector3d(0, 0, 0)}) {
    EXPECT_NEAR(rolling_share(ball, up, direction), 5.0 / 7.0, 1e-12);
  }
  // An ellipsoid of semi-axes 0.5, 0.3, 0.2 lying on its z axis (radius 0.2), rolling along y:
  // the rolling axis is z x y = -x, so I_e = I_x = m (0.3^2 + 0.2^2) / 5.
  const Rock egg = ellipsoid(1.0, 0.6, 0.4);
  const RollingBody lying = body_of(egg, Eigen::Quaterniond::Identity(), 0.2);
  const double m = egg.mass();
  const double inertia = m * (0.09 + 0.04) / 5.0;
  EXPECT_NEAR(rolling_share(lying, up, Eigen::Vector3d::UnitY()), m * 0.04 / (m * 0.04 + inertia), 1e-12);
  // Rolling along x, about y: I_y = m (0.5^2 + 0.2^2) / 5, a larger share in rotation.
  EXPECT_NEAR(rolling_share(lying, up, Eigen::Vector3d::UnitX()), m * 0.04 / (m * 0.04 + m * 0.29 / 5.0), 1e-12);
}

TEST(Rolling, SpinAndRotationEnergyOfRollingWithoutSlip) {
  Rock sphere;
  const RollingBody ball = body_of(sphere, Eigen::Quaterniond::Identity(), 0.5);
  const Eigen::Vector3d normal = Eigen::Vector3d(0.3, 0.0, 1.0).normalized();
  const Eigen::Vector3d velocity = 4.0 * normal.cross(Eigen::Vector3d::UnitY()).cross(normal).normalized();
  const Eigen::Vector3d spin = rolling_spin(ball.radius, normal, velocity);
  // The contact point, 0.5 m below the centre along -n, does not move: v + w x (-r n) = 0.
  EXPECT_LT((velocity + spin.cross(-0.5 * normal)).norm(), 1e-12);
  // Rotation carries 2/5 of the translation's energy: the total is 7/5 of it, 1/A.
  const double translation = 0.5 * ball.mass * velocity.squaredNorm();
  EXPECT_NEAR(rotation_energy(ball, spin) / translation, 2.0 / 5.0, 1e-12);
}

// Friction at the contact point conserves the angular momentum about it along the rolling axis:
// a sphere without spin rolls on at 5/7 of its speed; one already rolling keeps its speed; one
// spinning backwards (backspin) rolls slower; the rolling rock never has more energy than it
// brought.
TEST(Rolling, StartingToRollConservesAngularMomentumAboutTheContactPoint) {
  Rock sphere;
  const RollingBody ball = body_of(sphere, Eigen::Quaterniond::Identity(), 0.5);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d v(6.0, 0.0, 0.0);
  EXPECT_NEAR(start_rolling(ball, up, v, Eigen::Vector3d::Zero()).x(), 5.0 / 7.0 * 6.0, 1e-12);
  EXPECT_NEAR(start_rolling(ball, up, v, rolling_spin(ball.radius, up, v)).x(), 6.0, 1e-12);
  const Eigen::Vector3d backspin = -0.5 * rolling_spin(ball.radius, up, v);
  const double u = start_rolling(ball, up, v, backspin).x();
  EXPECT_NEAR(u, 5.0 / 7.0 * 6.0 - 2.0 / 7.0 * 3.0, 1e-12);
  // Angular momentum about the contact point, m r v + I w_e, before and after.
  const double inertia = 0.4 * ball.mass * 0.25;
  const Eigen::Vector3d axis = up.cross(Eigen::Vector3d::UnitX());
  EXPECT_NEAR(ball.mass * 0.5 * 6.0 + inertia * backspin.dot(axis), ball.mass * 0.5 * u + inertia * u / 0.5, 1e-9);
  // A rock spinning hard backwards stops rather than rolls back; one spinning hard forwards rolls
  // faster, with no more energy than it brought.
  EXPECT_EQ(start_rolling(ball, up, v, -10.0 * rolling_spin(ball.radius, up, v)).norm(), 0.0);
  const Eigen::Vector3d topspin = 3.0 * rolling_spin(ball.radius, up, v);
  const Eigen::Vector3d after = start_rolling(ball, up, v, topspin);
  const double brought = 0.5 * ball.mass * v.squaredNorm() + rotation_energy(ball, topspin);
  const double kept = 0.5 * ball.mass * after.squaredNorm() + rotation_energy(ball, rolling_spin(ball.radius, up, after));
  EXPECT_GT(after.x(), 6.0);
  EXPECT_LE(kept, brought * (1.0 + 1e-12));
}

}  // namespace
}  // namespace talus
