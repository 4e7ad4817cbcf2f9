// Tests of the neighbour grid (paper 4.1): exactly the brute-force pairs, in a fixed order.
#include "talus/mudflow/neighbour_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

// A random cloud of particles over a 40 m x 30 m area with support radii 1-4 m.
ParticleSet random_cloud(std::size_t count, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> x(-20.0, 20.0), y(100.0, 130.0), radius(1.0, 4.0);
  ParticleSet p;
  for (std::size_t k = 0; k < count; ++k) p.add(1.0, {x(generator), y(generator), 0.0}, {0, 0, 0}, radius(generator));
  return p;
}

// The pairs (i, j), i < j, closer than max(R_i, R_j): the brute-force reference.
std::vector<std::pair<std::uint32_t, std::uint32_t>> brute_force_pairs(const ParticleSet& p) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    for (std::uint32_t j = i + 1; j < p.size(); ++j) {
      const double reach = std::max(p.radius[i], p.radius[j]);
      if (std::hypot(p.x[i] - p.x[j], p.y[i] - p.y[j]) < reach) pairs.push_back({i, j});
    }
  }
  return pairs;
}

// The same pairs from the grid: candidates within the largest radius, filtered by distance.
std::vector<std::pair<std::uint32_t, std::uint32_t>> grid_pairs(const ParticleSet& p, const NeighbourGrid& grid) {
  double largest = 0;
  for (double r : p.radius) largest = std::max(largest, r);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    grid.for_each_candidate(p.x[i], p.y[i], largest, [&](std::uint32_t j) {
      if (j <= i) return;
      const double reach = std::max(p.radius[i], p.radius[j]);
      if (std::hypot(p.x[i] - p.x[j], p.y[i] - p.y[j]) < reach) pairs.push_back({i, j});
    });
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

TEST(NeighbourGrid, FindsExactlyTheBruteForcePairs) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    const ParticleSet p = random_cloud(400, seed);
    NeighbourGrid grid;
    grid.rebuild(p, 0.0);
    const auto expected = brute_force_pairs(p);
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(grid_pairs(p, grid), expected) << seed;
  }
}

TEST(NeighbourGrid, BinsAreAtLeastTheLargestRadiusAndRangesBeyondABinWork) {
  const ParticleSet p = random_cloud(300, 7);
  NeighbourGrid grid;
  grid.rebuild(p, 0.5);
  EXPECT_GE(grid.bin_size(), *std::max_element(p.radius.begin(), p.radius.end()));
  // A range of 2.5 bins still sees every particle within it.
  const double range = 2.5 * grid.bin_size();
  std::vector<std::uint32_t> seen;
  grid.for_each_candidate(0.0, 115.0, range, [&](std::uint32_t j) { seen.push_back(j); });
  for (std::uint32_t j = 0; j < p.size(); ++j) {
    if (std::hypot(p.x[j], p.y[j] - 115.0) < range) {
      EXPECT_NE(std::find(seen.begin(), seen.end(), j), seen.end()) << j;
    }
  }
}

TEST(NeighbourGrid, CandidatesComeInBinThenIndexOrderWhateverTheInsertionHistory) {
  ParticleSet p = random_cloud(200, 11);
  NeighbourGrid fresh;
  fresh.rebuild(p, 0.0);
  std::vector<std::uint32_t> first;
  fresh.for_each_candidate(5.0, 110.0, fresh.bin_size(), [&](std::uint32_t j) { first.push_back(j); });
  // Within one bin the indices ascend; a second grid built the same way visits the same order.
  NeighbourGrid again;
  again.rebuild(p, 0.0);
  std::vector<std::uint32_t> second;
  again.for_each_candidate(5.0, 110.0, again.bin_size(), [&](std::uint32_t j) { second.push_back(j); });
  EXPECT_EQ(first, second);
  EXPECT_FALSE(first.empty());
}

TEST(NeighbourGrid, UpdateRebinsOnlyWhenAParticleChangedBin) {
  ParticleSet p = random_cloud(100, 5);
  NeighbourGrid grid;
  grid.rebuild(p, 0.0);
  EXPECT_FALSE(grid.update(p));
  // A particle moved by three bins has changed bin.
  p.x[0] += 3.0 * grid.bin_size();
  EXPECT_TRUE(grid.update(p));
  EXPECT_FALSE(grid.update(p));
  p.add(1.0, {0.0, 115.0, 0.0}, {0, 0, 0}, 1.0);
  EXPECT_TRUE(grid.update(p));
  EXPECT_EQ(grid.particle_count(), p.size());
  // After the update the pairs are again exactly the brute-force ones.
  EXPECT_EQ(grid_pairs(p, grid), brute_force_pairs(p));
}

}  // namespace
}  // namespace talus
