// Tests of the areal density, depth and basal pressure of the columns (paper 4.1; docs/mudflow.md
// "State equation"), and of the pair search with smoothing radii that differ.
#include "talus/mudflow/flow_density.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus {
namespace {

constexpr double kRho = 2000.0;  // kg/m3

std::vector<NeighbourList> all_lists(std::size_t n) { return std::vector<NeighbourList>(n); }

// Densities of every listed particle (all by default), with the smoothing radii of the stored
// densities, as one evaluation of the simulation computes them.
std::vector<double> sum_all(ParticleSet& p, std::vector<double>& smoothing, std::vector<NeighbourList>& lists) {
  const std::size_t n = p.size();
  smoothing.resize(n);
  for (std::size_t i = 0; i < n; ++i) smoothing[i] = smoothing_radius(p, i);
  PairSearch search;
  search.rebuild(p, smoothing, *std::min_element(p.radius.begin(), p.radius.end()));
  std::vector<double> sigma(n);
  for (std::size_t i = 0; i < n; ++i) sigma[i] = gather_density(p, search, i, smoothing[i], lists[i]);
  return sigma;
}

TEST(FlowDensity, UniformLatticeHasTheReleasedDepthAndHydrostaticPressure) {
  // 30 x 30 particles 0.5 m apart, each a 0.5 m x 0.5 m column 2 m deep, on flat ground.
  const double spacing = 0.5, depth = 2.0;
  ParticleSet p;
  for (int a = 0; a < 30; ++a) {
    for (int b = 0; b < 30; ++b) {
      p.add(kRho * depth * spacing * spacing, {a * spacing, b * spacing, 0.0}, {0, 0, 0}, kSupportPerSpacing * spacing);
    }
  }
  std::vector<double> smoothing;
  auto lists = all_lists(p.size());
  const std::vector<double> sigma = sum_all(p, smoothing, lists);
  const ColumnConstants constants{kRho, 9.81};
  for (std::size_t i = 0; i < p.size(); ++i) set_column_state(p, i, sigma[i], 1.0, constants);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int a = static_cast<int>(i / 30), b = static_cast<int>(i % 30);
    if (std::min({a, b, 29 - a, 29 - b}) < 3) continue;  // interior: the kernel is complete
    // 2.5%: the Wendland C2 sum over a square lattice at R = 2.4 spacings is 1.018 columns
    // (the lattice sum of W s^2; 1.005 at R = 3 spacings).
    EXPECT_NEAR(p.depth[i], depth, 0.025 * depth) << i;
    EXPECT_DOUBLE_EQ(p.pressure[i], kRho * 9.81 * p.depth[i]);
  }
  // On a slope of cos(theta) = 0.8 the depth normal to the ground and the pressure scale.
  set_column_state(p, 0, 1000.0, 0.8, constants);
  EXPECT_DOUBLE_EQ(p.depth[0], 1000.0 * 0.8 / kRho);
  EXPECT_DOUBLE_EQ(p.pressure[0], kRho * 9.81 * 0.8 * p.depth[0]);
}

TEST(FlowDensity, SmoothingRadiusFollowsTheDensityWithinItsBounds) {
  ParticleSet p;
  p.add(100.0, {0, 0, 0}, {0, 0, 0}, 1.0);
  EXPECT_EQ(smoothing_radius(p, 0), 1.0);  // no density yet
  p.density[0] = 100.0 * kernel_value(0.0, 1.0);  // alone: 2.4 sqrt(pi / 7) R = 1.608 R
  EXPECT_NEAR(smoothing_radius(p, 0), kSupportPerSpacing * std::sqrt(std::acos(-1.0) / 7.0), 1e-12);
  p.density[0] = 1e6;  // dense: never below R
  EXPECT_EQ(smoothing_radius(p, 0), 1.0);
  p.density[0] = 1e-6;  // thin: at most kLargestSmoothingGrowth R
  EXPECT_EQ(smoothing_radius(p, 0), kLargestSmoothingGrowth);
}

// Crowded fusion's floor (docs/mudflow.md section 8): a particle of support radius 2 m in mud
// four times as dense as its spacing holds sums over 1 m (2.4 sqrt(m / sigma)) when the floor
// allows it, over the floor when that is larger, and never over less than its own R without one.
TEST(FlowDensity, SmoothingRadiusFloorIsTheSmallestRadiusGiven) {
  ParticleSet p;
  p.add(100.0, {0, 0, 0}, {0, 0, 0}, 2.0);
  const double spacing = 2.0 / kSupportPerSpacing;       // m
  p.density[0] = 4.0 * 100.0 / (spacing * spacing);      // kg/m2: natural radius 1 m
  EXPECT_NEAR(natural_smoothing_radius(p, 0), 1.0, 1e-12);
  EXPECT_EQ(smoothing_radius(p, 0), 2.0);                // no floor given: its own R
  EXPECT_NEAR(smoothing_radius(p, 0, 0.5), 1.0, 1e-12);  // floor below: the natural radius
  EXPECT_EQ(smoothing_radius(p, 0, 1.25), 1.25);         // floor above it: the floor
  EXPECT_EQ(smoothing_radius(p, 0, 3.0), 2.0);           // a floor above R is R
  p.density[0] = 1e-6;                                   // thin: still at most kLargestSmoothingGrowth R
  EXPECT_EQ(smoothing_radius(p, 0, 0.5), 2.0 * kLargestSmoothingGrowth);
}

TEST(FlowDensity, PairsAreTheBruteForcePairsWithSymmetricKernels) {
  // A cloud of columns of varied mass and density, so the smoothing radii range over [R, 4 R].
  std::mt19937 generator(3);
  std::uniform_real_distribution<double> coordinate(0.0, 12.0), mass(50.0, 150.0), density(1.0, 500.0);
  ParticleSet p;
  for (int k = 0; k < 250; ++k) {
    const std::size_t i = p.add(mass(generator), {coordinate(generator), coordinate(generator), 0.0}, {0, 0, 0}, 1.0);
    p.density[i] = density(generator);
  }
  std::vector<double> smoothing;
  auto lists = all_lists(p.size());
  const std::vector<double> sigma = sum_all(p, smoothing, lists);
  ASSERT_GT(*std::max_element(smoothing.begin(), smoothing.end()), 3.0);  // classes 0, 1 and 2
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::set<std::uint32_t> expected;
    double expected_sigma = p.mass[i] * kernel_value(0.0, smoothing[i]);
    for (std::uint32_t j = 0; j < p.size(); ++j) {
      const double r = std::hypot(p.x[i] - p.x[j], p.y[i] - p.y[j]);
      if (j == i || r >= std::max(smoothing[i], smoothing[j])) continue;
      expected.insert(j);
      expected_sigma += p.mass[j] * 0.5 * (kernel_value(r, smoothing[i]) + kernel_value(r, smoothing[j]));
    }
    std::set<std::uint32_t> found;
    for (const NeighbourPair& pair : lists[i]) EXPECT_TRUE(found.insert(pair.index).second) << "duplicate pair";
    EXPECT_EQ(found, expected) << i;
    // The inline kernel equals kernel_value: 1e-12 relative (summation order differs).
    EXPECT_NEAR(sigma[i], expected_sigma, 1e-12 * expected_sigma) << i;
    for (const NeighbourPair& pair : lists[i]) {
      const std::size_t j = pair.index;
      const double r = std::hypot(p.x[i] - p.x[j], p.y[i] - p.y[j]);
      const double slope = 0.5 * (kernel_slope(r, smoothing[i]) + kernel_slope(r, smoothing[j]));
      EXPECT_NEAR(pair.gradient_factor, slope / r, 1e-12 * std::abs(slope / r));
      // The same factor in j's list: pair forces are equal and opposite.
      const auto back = std::find_if(lists[j].begin(), lists[j].end(), [&](const NeighbourPair& q) { return q.index == i; });
      ASSERT_NE(back, lists[j].end());
      EXPECT_EQ(back->gradient_factor, pair.gradient_factor);
    }
  }
}

}  // namespace
}  // namespace talus
