// Tests of the structure-of-arrays particle store (paper 4.1).
#include "talus/mudflow/particle_set.hpp"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

// Three particles with distinct values in every array, so a wrong permutation shows.
ParticleSet three_particles() {
  ParticleSet p;
  for (int k = 0; k < 3; ++k) {
    const double d = k + 1.0;
    const std::size_t i = p.add(10.0 * d, {d, 2.0 * d, 3.0 * d}, {-d, 0.5 * d, 0.0}, 0.1 * d);
    p.ax[i] = 4.0 * d;
    p.density[i] = 5.0 * d;
    p.depth[i] = 6.0 * d;
    p.pressure[i] = 7.0 * d;
    p.still_time[i] = 8.0 * d;
    p.level[i] = static_cast<std::uint8_t>(k);
    p.state[i] = k == 1 ? ParticleState::deposited : ParticleState::flowing;
  }
  return p;
}

TEST(ParticleSet, AddStartsAFlowingParticleAtLevelZero) {
  ParticleSet p;
  const std::size_t i = p.add(2.0, {1, 2, 3}, {4, 5, 6}, 0.7);
  EXPECT_EQ(i, 0u);
  EXPECT_EQ(p.size(), 1u);
  EXPECT_EQ(p.position(0), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(p.velocity(0), Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(p.radius[0], 0.7);
  EXPECT_EQ(p.density[0], 0.0);
  EXPECT_EQ(p.level[0], 0);
  EXPECT_EQ(p.state[0], ParticleState::flowing);
}

TEST(ParticleSet, KeepOnlyKeepsTheFlaggedInOrder) {
  ParticleSet p = three_particles();
  p.keep_only({1, 0, 1});
  ASSERT_EQ(p.size(), 2u);
  // Every array follows: particle 0 then particle 2 of the original set.
  for (std::size_t k = 0; k < 2; ++k) {
    const double d = k == 0 ? 1.0 : 3.0;
    EXPECT_EQ(p.mass[k], 10.0 * d);
    EXPECT_EQ(p.position(k), Eigen::Vector3d(d, 2.0 * d, 3.0 * d));
    EXPECT_EQ(p.velocity(k), Eigen::Vector3d(-d, 0.5 * d, 0.0));
    EXPECT_EQ(p.ax[k], 4.0 * d);
    EXPECT_EQ(p.density[k], 5.0 * d);
    EXPECT_EQ(p.depth[k], 6.0 * d);
    EXPECT_EQ(p.pressure[k], 7.0 * d);
    EXPECT_EQ(p.radius[k], 0.1 * d);
    EXPECT_EQ(p.still_time[k], 8.0 * d);
    EXPECT_EQ(p.level[k], k == 0 ? 0 : 2);
    EXPECT_EQ(p.state[k], ParticleState::flowing);
  }
}

TEST(ParticleSet, ReorderPermutesEveryArray) {
  ParticleSet p = three_particles();
  p.reorder({2, 0, 1});
  ASSERT_EQ(p.size(), 3u);
  const double expected[3] = {3.0, 1.0, 2.0};
  for (std::size_t k = 0; k < 3; ++k) {
    const double d = expected[k];
    EXPECT_EQ(p.mass[k], 10.0 * d);
    EXPECT_EQ(p.x[k], d);
    EXPECT_EQ(p.vy[k], 0.5 * d);
    EXPECT_EQ(p.pressure[k], 7.0 * d);
    EXPECT_EQ(p.level[k], static_cast<std::uint8_t>(d - 1.0));
  }
  EXPECT_EQ(p.state[2], ParticleState::deposited);
}

TEST(ParticleSet, TotalsOfMassMomentumAndKineticEnergy) {
  const ParticleSet p = three_particles();
  // 10 + 20 + 30 kg; momentum sum m v; energy sum m |v|^2 / 2 (exact in binary for these values).
  EXPECT_DOUBLE_EQ(p.total_mass(), 60.0);
  EXPECT_TRUE(p.total_momentum().isApprox(Eigen::Vector3d(-140.0, 70.0, 0.0), 1e-15));
  EXPECT_DOUBLE_EQ(p.kinetic_energy(), 0.5 * 1.25 * (10.0 + 80.0 + 270.0));
}

}  // namespace
}  // namespace talus
