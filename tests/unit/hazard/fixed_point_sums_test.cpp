// Tests of FixedPointSums (docs/architecture.md section 2, "Statistical maps": energy losses).
#include "talus/hazard/fixed_point_sums.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

TEST(FixedPointSums, RoundsEachValueToTheNearestQuantum) {
  FixedPointSums sums(2, 1e-3);
  sums.add(0, 1.2344);     // 1234 mJ
  sums.add(0, 0.0006);     // 1 mJ
  sums.add(1, -2.5);
  EXPECT_EQ(sums.quanta(0), 1235);
  EXPECT_DOUBLE_EQ(sums.total(0), 1.235);
  EXPECT_EQ(sums.quanta(1), -2500);
  EXPECT_FALSE(sums.saturated());
}

TEST(FixedPointSums, MergeIsExactInAnyOrder) {
  constexpr std::size_t kCells = 6;
  std::mt19937_64 random(11);
  std::lognormal_distribution<double> value(8.0, 3.0);   // J, across many orders of magnitude
  std::uniform_int_distribution<std::size_t> cell(0, kCells - 1);
  std::vector<FixedPointSums> parts(7, FixedPointSums(kCells, 1e-3));
  FixedPointSums single(kCells, 1e-3);
  for (int k = 0; k < 5000; ++k) {
    const std::size_t c = cell(random);
    const double v = value(random);
    single.add(c, v);
    parts[static_cast<std::size_t>(k) % parts.size()].add(c, v);
  }
  std::vector<std::size_t> order(parts.size());
  std::iota(order.begin(), order.end(), 0);
  for (int trial = 0; trial < 5; ++trial) {
    std::shuffle(order.begin(), order.end(), random);
    FixedPointSums merged(kCells, 1e-3);
    for (const std::size_t p : order) merged.merge(parts[p]);
    for (std::size_t c = 0; c < kCells; ++c) EXPECT_EQ(merged.quanta(c), single.quanta(c)) << "cell " << c;
  }
  // A tree of merges gives the same bits as a chain.
  FixedPointSums left(kCells, 1e-3);
  FixedPointSums right(kCells, 1e-3);
  for (std::size_t p = 0; p < parts.size(); ++p) (p < 3 ? left : right).merge(parts[p]);
  right.merge(left);
  for (std::size_t c = 0; c < kCells; ++c) EXPECT_EQ(right.quanta(c), single.quanta(c));
}

TEST(FixedPointSums, GuardsOverflowBySaturating) {
  constexpr std::int64_t top = std::numeric_limits<std::int64_t>::max();
  FixedPointSums sums(3, 1.0);
  sums.add(0, 9e18);
  sums.add(0, 9e18);
  EXPECT_EQ(sums.quanta(0), top);
  EXPECT_TRUE(sums.saturated());

  FixedPointSums huge(3, 1e-3);
  huge.add(1, 1e30);                                        // beyond int64 quanta at once
  EXPECT_EQ(huge.quanta(1), top);
  EXPECT_TRUE(huge.saturated());

  FixedPointSums nan(3, 1.0);
  nan.add(2, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(nan.quanta(2), 0);
  EXPECT_TRUE(nan.saturated());

  FixedPointSums fine(3, 1.0);
  EXPECT_FALSE(fine.saturated());
  fine.merge(sums);                                         // the flag travels with merges
  EXPECT_TRUE(fine.saturated());
  EXPECT_EQ(fine.quanta(0), top);
}

TEST(FixedPointSums, RefusesBadQuantaAndMismatchedMerges) {
  EXPECT_THROW(FixedPointSums(2, 0.0), std::invalid_argument);
  EXPECT_THROW(FixedPointSums(2, -1.0), std::invalid_argument);
  FixedPointSums a(2, 1e-3);
  EXPECT_THROW(a.merge(FixedPointSums(2, 1.0)), std::invalid_argument);
  EXPECT_THROW(a.merge(FixedPointSums(3, 1e-3)), std::invalid_argument);
}

}  // namespace
}  // namespace talus
