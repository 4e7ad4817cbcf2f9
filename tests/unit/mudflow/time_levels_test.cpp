// Tests of the per-particle power-of-two time steps and their limiter (paper 4.2; Saitoh &
// Makino 2009).
#include "talus/mudflow/time_levels.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

TEST(TimeLevels, StableStepIsTheSmallestOfTheCriteria) {
  const StepCriteria criteria{0.3, 0.0};
  // Courant: 0.3 x 2 m / (3 + 1) m/s = 0.15 s with a neighbour closing in at 1 m/s; force:
  // 0.3 sqrt(2 / 0.5) = 0.6 s.
  EXPECT_DOUBLE_EQ(stable_step(2.0, 3.0, 1.0, 0.0, 0.5, criteria), 0.15);
  // Force: 0.3 sqrt(2 / 50) = 0.06 s.
  EXPECT_DOUBLE_EQ(stable_step(2.0, 3.0, 1.0, 0.0, 50.0, criteria), 0.3 * std::sqrt(2.0 / 50.0));
  // Viscous limit s^2 / (8 nu) = 4 / 80 = 0.05 s.
  EXPECT_DOUBLE_EQ(stable_step(2.0, 3.0, 1.0, 0.0, 0.5, {0.3, 10.0}), 0.05);
  // At rest with no force and no viscosity nothing limits the step.
  EXPECT_TRUE(std::isinf(stable_step(2.0, 0.0, 0.0, 0.0, 0.0, criteria)));
}

TEST(TimeLevels, TheFlowsOwnSpeedLimitsTheStepOnlyThroughTheGround) {
  // Galilean invariance: a flow at 50 m/s whose neighbours keep their distances takes the step
  // of the same flow at rest, 0.3 x 2 / 3 = 0.2 s, unless the ground limit asks for less.
  const StepCriteria no_ground{0.3, 0.0};
  EXPECT_DOUBLE_EQ(stable_step(2.0, 3.0, 0.0, 50.0, 0.0, no_ground), 0.2);
  // Ground: at most 1.5 cells of 5 m at 50 m/s, 0.15 s.
  const StepCriteria ground{0.3, 0.0, 5.0, 1.5};
  EXPECT_DOUBLE_EQ(stable_step(2.0, 3.0, 0.0, 50.0, 0.0, ground), 0.15);
  EXPECT_DOUBLE_EQ(stable_step(2.0, 3.0, 0.0, 10.0, 0.0, ground), 0.2);
}

TEST(TimeLevels, ApproachSpeedIsTheRelativeVelocityAlongTheLineOfCentres) {
  // dx = x_i - x_j, dv = u_i - u_j: a neighbour 2 m ahead (+x) and 3 m/s slower closes at 3 m/s.
  EXPECT_DOUBLE_EQ(approach_speed(-2.0, 0.0, 3.0, 0.0), 3.0);
  // The same neighbour 2 m behind recedes.
  EXPECT_DOUBLE_EQ(approach_speed(2.0, 0.0, 3.0, 0.0), -3.0);
  // Crossing at right angles to the line of centres, it neither closes in nor recedes.
  EXPECT_DOUBLE_EQ(approach_speed(0.0, -2.0, 5.0, 0.0), 0.0);
  // Along a diagonal 3-4-5: only the part of dv along the line counts.
  EXPECT_DOUBLE_EQ(approach_speed(-3.0, -4.0, 5.0, 0.0), 3.0);
  // Two feet on one spot have no line of centres.
  EXPECT_DOUBLE_EQ(approach_speed(0.0, 0.0, 5.0, 1.0), 0.0);
}

TEST(TimeLevels, LevelIsTheShallowestWhoseStepMeetsTheCriterion) {
  EXPECT_EQ(level_for_step(1.0, 0.5, 12), 0);
  EXPECT_EQ(level_for_step(0.5, 0.5, 12), 0);
  EXPECT_EQ(level_for_step(0.49, 0.5, 12), 1);
  EXPECT_EQ(level_for_step(0.25, 0.5, 12), 1);
  EXPECT_EQ(level_for_step(0.2, 0.5, 12), 2);
  EXPECT_EQ(level_for_step(1e-9, 0.5, 12), 12);  // capped at the deepest level
  EXPECT_EQ(level_for_step(std::nan(""), 0.5, 12), 12);
  for (double step = 1e-3; step < 1.0; step *= 1.37) {
    const int level = level_for_step(step, 0.5, 20);
    EXPECT_LE(std::ldexp(0.5, -level), step);
    if (level > 0) {
      EXPECT_GT(std::ldexp(0.5, -(level - 1)), step);
    }
  }
}

TEST(TimeLevels, LimiterKeepsStepsWithinFourTimesTheNeighbours) {
  const NeighbourList neighbours{{1, 0.0}, {2, 0.0}, {3, 0.0}};
  const std::vector<int> levels{0, 1, 6, -1};  // particle 3 is ignored (deposited)
  const auto level_of = [&](std::uint32_t j) { return levels[j]; };
  EXPECT_EQ(limited_level(0, neighbours, level_of), 4);  // 6 - 2
  EXPECT_EQ(limited_level(5, neighbours, level_of), 5);
  EXPECT_EQ(limited_level(2, {}, level_of), 2);
}

TEST(TimeLevels, LongerStepsStartOnlyOnTheirOwnGrid) {
  const int finest = 10;  // 1024 ticks per coarse step
  EXPECT_EQ(ticks_per_step(0, finest), 1024u);
  EXPECT_EQ(ticks_per_step(3, finest), 128u);
  EXPECT_EQ(aligned_level(0, 0, finest), 0);
  EXPECT_EQ(aligned_level(0, 512, finest), 1);    // halfway: a half step at most
  EXPECT_EQ(aligned_level(1, 512, finest), 1);
  EXPECT_EQ(aligned_level(0, 384, finest), 3);    // 384 = 3 x 128
  EXPECT_EQ(aligned_level(5, 384, finest), 5);    // deeper levels are always aligned there
  EXPECT_EQ(aligned_level(0, 1, finest), finest);
}

}  // namespace
}  // namespace talus
