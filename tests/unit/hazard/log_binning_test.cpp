// Tests of LogBinning (docs/architecture.md section 2, "Statistical maps": quantile bins).
#include "talus/hazard/log_binning.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace talus {
namespace {

TEST(LogBinning, EdgesAreLogarithmic) {
  const LogBinning binning(1e-3, 1e6, 20);
  EXPECT_EQ(binning.bin_count(), 180);
  EXPECT_DOUBLE_EQ(binning.min(), 1e-3);
  EXPECT_NEAR(binning.max(), 1e6, 1e-6);
  EXPECT_NEAR(binning.bin_ratio(), std::pow(10.0, 0.05), 1e-15);
  for (int k = 0; k < binning.bin_count(); ++k) {
    EXPECT_NEAR(binning.upper(k) / binning.lower(k), binning.bin_ratio(), 1e-12);
  }
  EXPECT_NEAR(binning.lower(20), 1e-2, 1e-15);
}

TEST(LogBinning, LastEdgeCoversMax) {
  const LogBinning binning(1.0, 50.0, 1);   // 1, 10, 100
  EXPECT_EQ(binning.bin_count(), 2);
  EXPECT_DOUBLE_EQ(binning.max(), 100.0);
}

TEST(LogBinning, EveryValueLiesInsideItsBin) {
  const LogBinning binning(1e-2, 1e12, 20);
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> exponent(-2.0, 12.0);
  for (int i = 0; i < 20000; ++i) {
    const double value = std::pow(10.0, exponent(random));
    const int bin = binning.bin_of(value);
    if (bin == binning.overflow()) {
      EXPECT_GE(value, binning.max());
      continue;
    }
    ASSERT_GE(bin, 0);
    EXPECT_LE(binning.lower(bin), value);
    EXPECT_LT(value, binning.upper(bin));
  }
  // The edges themselves open their bins.
  for (int k = 0; k < binning.bin_count(); ++k) {
    EXPECT_EQ(binning.bin_of(binning.lower(k)), k);
    EXPECT_EQ(binning.bin_of(std::nextafter(binning.lower(k), 0.0)), k - 1);
  }
}

TEST(LogBinning, UnderflowAndOverflow) {
  const LogBinning binning(1e-3, 1e6, 20);
  EXPECT_EQ(binning.bin_of(0.0), LogBinning::underflow);
  EXPECT_EQ(binning.bin_of(-5.0), LogBinning::underflow);
  EXPECT_EQ(binning.bin_of(9e-4), LogBinning::underflow);
  EXPECT_EQ(binning.bin_of(std::numeric_limits<double>::quiet_NaN()), LogBinning::underflow);
  EXPECT_EQ(binning.bin_of(binning.max()), binning.overflow());
  EXPECT_EQ(binning.bin_of(std::numeric_limits<double>::infinity()), binning.overflow());
}

TEST(LogBinning, RefusesBadRanges) {
  EXPECT_THROW(LogBinning(0.0, 1.0, 20), std::invalid_argument);
  EXPECT_THROW(LogBinning(1.0, 1.0, 20), std::invalid_argument);
  EXPECT_THROW(LogBinning(1.0, 10.0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace talus
