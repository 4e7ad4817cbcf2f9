// Tests of the rock-fall source detection (issue 19, item 1; Loye et al. 2009): Horn's slope on
// planes, the decomposition of a known four-unit slope distribution, its cliff threshold against
// the crossing of the two steepest units' densities, and the mask with lithology classes.
#include "talus/hazard/rockfall_source_detection.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

GridSpec square_spec(int width, int height, double cell) {
  GridSpec spec;
  spec.width = width;
  spec.height = height;
  spec.geotransform = {0, cell, 0, 0, 0, -cell};
  return spec;
}

TEST(RockfallSourceDetection, HornsSlopeOfAPlaneIsItsAngleAndTheEdgeIsNodata) {
  const GridSpec spec = square_spec(6, 5, 2.0);
  Grid<double> plane(spec);
  for (int row = 0; row < 5; ++row) {
    for (int col = 0; col < 6; ++col) plane[plane.index(col, row)] = 100.0 + 0.5 * col * 2.0 - 0.25 * row * 2.0;
  }
  const Grid<float> slopes = slope_angles(plane);
  const double expected = std::atan(std::hypot(0.5, 0.25)) * 180.0 / std::numbers::pi;
  EXPECT_NEAR(slopes[slopes.index(2, 2)], expected, 1e-4);
  EXPECT_FALSE(slopes.is_valid(slopes.index(0, 2)));
  EXPECT_FALSE(slopes.is_valid(slopes.index(3, 4)));
}

// Slopes whose histogram is a known mixture: `count` cells per unit at the quantiles of its normal.
Grid<float> mixture(const std::vector<std::pair<SlopeUnit, int>>& units) {
  std::vector<float> values;
  for (const auto& [unit, count] : units) {
    for (int k = 0; k < count; ++k) {
      const double p = (k + 0.5) / count;  // a normal quantile by bisection of the CDF
      double low = -8, high = 8;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (low + high);
        (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? low : high) = mid;
      }
      values.push_back(static_cast<float>(std::clamp(unit.mean + unit.sd * low, 0.0, 89.9)));
    }
  }
  return Grid<float>(square_spec(static_cast<int>(values.size()), 1, 5.0), values);
}

TEST(RockfallSourceDetection, AKnownDistributionIsDecomposedAndItsCliffThresholdFound) {
  const std::vector<std::pair<SlopeUnit, int>> truth = {
      {{0, 4, 2}, 30000}, {{0, 18, 4}, 40000}, {{0, 36, 6}, 25000}, {{0, 60, 6}, 5000}};
  const auto units = slope_units(mixture(truth));
  EXPECT_NEAR(units[3].mean, 60.0, 1.0);
  EXPECT_NEAR(units[3].sd, 6.0, 1.0);
  EXPECT_NEAR(units[3].weight, 0.05, 0.01);
  EXPECT_NEAR(units[2].mean, 36.0, 1.0);
  // Where 0.05 N(60, 6) overtakes 0.25 N(36, 6): (x - 36)^2 - (x - 60)^2 = 72 ln 5, x = 48 + 3 ln 5 / 2.
  const double crossing = 48.0 + 1.5 * std::log(5.0);
  const auto threshold = cliff_threshold(units);
  ASSERT_TRUE(threshold.has_value());
  EXPECT_NEAR(*threshold, crossing, 1.0);
}

TEST(RockfallSourceDetection, NoCliffUnitGivesNoThreshold) {
  // A "cliff" unit that is only a narrow bump on the steep slopes, never dominant up to 90 degrees.
  const std::array<SlopeUnit, 4> units = {{{0.3, 5, 2}, {0.3, 15, 3}, {0.4, 30, 5}, {1e-6, 31, 3}}};
  EXPECT_FALSE(cliff_threshold(units).has_value());
}

TEST(RockfallSourceDetection, TheMaskKeepsSteepCellsOfTheGivenClasses) {
  const GridSpec spec = square_spec(5, 1, 5.0);
  Grid<float> slopes(spec, std::vector<float>{30, 50, 50, 70, static_cast<float>(spec.nodata)});
  const Grid<int> lithology(spec, std::vector<int>{6, 6, 3, 6, 6});
  EXPECT_EQ(source_mask(slopes, 50, lithology, {}).values(), (std::vector<float>{0, 1, 1, 1, 0}));
  EXPECT_EQ(source_mask(slopes, 50, lithology, {6}).values(), (std::vector<float>{0, 1, 0, 1, 0}));
}

}  // namespace
}  // namespace talus
