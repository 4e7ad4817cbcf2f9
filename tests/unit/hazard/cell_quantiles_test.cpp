// Tests of CellQuantiles (docs/architecture.md section 2, "Statistical maps": per-cell percentiles).
#include "talus/hazard/cell_quantiles.hpp"

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

LogBinning test_binning() { return LogBinning(1e-3, 1e6, 20); }

TEST(CellQuantiles, AllocatesOnlyForReachedCells) {
  CellQuantiles quantiles(1000, test_binning());
  EXPECT_EQ(quantiles.reached_cells(), 0u);
  quantiles.add(17, 3.0);
  quantiles.add(17, 4.0);
  quantiles.add(900, 0.0);
  EXPECT_EQ(quantiles.reached_cells(), 2u);
  EXPECT_EQ(quantiles.count(17), 2u);
  EXPECT_EQ(quantiles.count(900), 1u);
  EXPECT_EQ(quantiles.count(5), 0u);
  EXPECT_EQ(quantiles.quantile(5, 0.95), 0.0);
  EXPECT_EQ(quantiles.quantile(900, 0.95), 0.0);
  const double q = quantiles.quantile(17, 1.0);
  EXPECT_GT(q, 4.0 / test_binning().bin_ratio());
  EXPECT_LT(q, 4.0 * test_binning().bin_ratio());
}

TEST(CellQuantiles, MergeInAnyOrderEqualsOneAccumulation) {
  constexpr std::size_t kCells = 50;
  std::mt19937_64 random(21);
  std::lognormal_distribution<double> value(3.0, 3.0);
  std::uniform_int_distribution<std::size_t> cell(0, kCells / 2);   // half the cells stay empty
  CellQuantiles single(kCells, test_binning());
  std::vector<CellQuantiles> parts(3, CellQuantiles(kCells, test_binning()));
  for (int i = 0; i < 4000; ++i) {
    const std::size_t c = cell(random);
    const double v = value(random);
    single.add(c, v);
    parts[static_cast<std::size_t>(i * 7 + static_cast<int>(c)) % parts.size()].add(c, v);
  }
  std::vector<std::size_t> order(parts.size());
  std::iota(order.begin(), order.end(), 0);
  do {
    CellQuantiles merged(kCells, test_binning());
    for (const std::size_t p : order) merged.merge(parts[p]);
    EXPECT_EQ(merged.reached_cells(), single.reached_cells());
    for (std::size_t c = 0; c < kCells; ++c) {
      EXPECT_EQ(merged.count(c), single.count(c));
      for (const double q : {0.5, 0.95, 1.0}) EXPECT_EQ(merged.quantile(c, q), single.quantile(c, q)) << "cell " << c;
    }
  } while (std::next_permutation(order.begin(), order.end()));
}

TEST(CellQuantiles, RefusesMismatchedMerges) {
  CellQuantiles a(10, test_binning());
  EXPECT_THROW(a.merge(CellQuantiles(11, test_binning())), std::invalid_argument);
  EXPECT_THROW(a.merge(CellQuantiles(10, LogBinning(1e-3, 1e6, 10))), std::invalid_argument);
}

TEST(CellQuantiles, MemoryGrowsWithReachedCellsOnly) {
  CellQuantiles quantiles(100000, test_binning());
  const std::size_t empty = quantiles.memory_bytes();
  EXPECT_LE(empty, sizeof(CellQuantiles) + 100000 * sizeof(std::uint32_t));
  for (std::size_t c = 0; c < 100; ++c) quantiles.add(c, 1.0 + static_cast<double>(c));
  const std::size_t per_reached_cell = (quantiles.memory_bytes() - empty) / 100;
  // The histogram record, its cell index, a window of one bin plus slack (9 bins), and the
  // spare capacity of the growing vectors.
  EXPECT_LE(per_reached_cell, 2 * sizeof(LogHistogram) + 2 * sizeof(std::uint32_t) + 9 * sizeof(std::uint32_t));
}

}  // namespace
}  // namespace talus
