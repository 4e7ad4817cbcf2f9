// Tests of LogHistogram (docs/architecture.md section 2, "Statistical maps": 95th percentiles over
// passages with bounded memory).
#include "talus/hazard/log_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

// The k-th smallest value with k = ceil(q N): the quantile the histogram estimates.
double exact_quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const auto n = static_cast<double>(values.size());
  const auto k = std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(q * n)), 1, values.size());
  return values[k - 1];
}

struct Distribution {
  const char* name;
  std::function<double(std::mt19937_64&)> draw;
};

TEST(LogHistogram, QuantilesWithinOneBinOfTheExactQuantile) {
  const LogBinning binning(1e-3, 1e6, 20);
  const std::vector<Distribution> distributions = {
      {"uniform", [](std::mt19937_64& r) { return std::uniform_real_distribution<double>(1.0, 1000.0)(r); }},
      {"lognormal", [](std::mt19937_64& r) { return std::lognormal_distribution<double>(2.0, 2.0)(r); }},
      {"exponential", [](std::mt19937_64& r) { return std::exponential_distribution<double>(0.01)(r); }},
      {"two modes", [](std::mt19937_64& r) {
         return std::bernoulli_distribution(0.3)(r) ? std::uniform_real_distribution<double>(0.01, 0.02)(r)
                                                     : std::uniform_real_distribution<double>(5e4, 9e4)(r);
       }},
  };
  std::mt19937_64 random(5);
  for (const Distribution& d : distributions) {
    for (const std::size_t n : {std::size_t{1}, std::size_t{3}, std::size_t{20}, std::size_t{1000}, std::size_t{100000}}) {
      LogHistogram histogram;
      std::vector<double> values;
      for (std::size_t i = 0; i < n; ++i) {
        values.push_back(d.draw(random));
        histogram.add(values.back(), binning);
      }
      ASSERT_EQ(histogram.count(), n);
      for (const double q : {0.0, 0.05, 0.5, 0.9, 0.95, 0.99, 1.0}) {
        const double exact = exact_quantile(values, q);
        const double estimate = histogram.quantile(q, binning);
        EXPECT_LT(estimate, exact * binning.bin_ratio()) << d.name << " n=" << n << " q=" << q;
        EXPECT_GT(estimate, exact / binning.bin_ratio()) << d.name << " n=" << n << " q=" << q;
      }
    }
  }
}

TEST(LogHistogram, InterpolatesLogLinearlyInsideABin) {
  const LogBinning binning(1.0, 1e4, 1);      // one bin per decade: 1-10, 10-100, ...
  LogHistogram histogram;
  for (int i = 0; i < 4; ++i) histogram.add(20.0 + i, binning);   // four values in [10, 100)
  // Rank q N = 2 of 4 is half-way through the bin: the geometric middle of 10 and 100.
  EXPECT_NEAR(histogram.quantile(0.5, binning), std::sqrt(10.0 * 100.0), 1e-9);
  EXPECT_NEAR(histogram.quantile(1.0, binning), 100.0, 1e-9);
}

TEST(LogHistogram, ZerosAreUnderflowAndBigValuesOverflow) {
  const LogBinning binning(1e-3, 1e6, 20);
  LogHistogram histogram;
  EXPECT_EQ(histogram.quantile(0.95, binning), 0.0);   // empty
  for (int i = 0; i < 96; ++i) histogram.add(0.0, binning);
  for (int i = 0; i < 4; ++i) histogram.add(5.0, binning);
  EXPECT_EQ(histogram.quantile(0.95, binning), 0.0);
  EXPECT_GT(histogram.quantile(0.97, binning), 5.0 / binning.bin_ratio());
  histogram.add(1e9, binning);
  EXPECT_EQ(histogram.quantile(1.0, binning), binning.max());
  EXPECT_EQ(histogram.count(), 101u);
}

TEST(LogHistogram, MergeEqualsOneAccumulationInAnyOrder) {
  const LogBinning binning(1e-2, 1e12, 20);
  std::mt19937_64 random(9);
  std::lognormal_distribution<double> value(6.0, 4.0);
  LogHistogram single;
  std::vector<LogHistogram> parts(5);
  for (int i = 0; i < 3000; ++i) {
    const double v = i % 17 == 0 ? 0.0 : value(random);
    single.add(v, binning);
    parts[static_cast<std::size_t>(i) % parts.size()].add(v, binning);
  }
  LogHistogram forward;
  for (const LogHistogram& p : parts) forward.merge(p);
  LogHistogram backward;
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) backward.merge(*it);
  for (const double q : {0.0, 0.1, 0.5, 0.95, 1.0}) {
    EXPECT_EQ(forward.quantile(q, binning), single.quantile(q, binning));
    EXPECT_EQ(backward.quantile(q, binning), single.quantile(q, binning));
  }
  EXPECT_EQ(forward.count(), single.count());
}

TEST(LogHistogram, MemoryStaysWithinTheBinning) {
  const LogBinning binning(1e-3, 1e6, 20);
  LogHistogram narrow;
  for (int i = 0; i < 1000; ++i) narrow.add(100.0 + i * 0.01, binning);
  EXPECT_LE(narrow.memory_bytes(), sizeof(LogHistogram) + 9 * sizeof(std::uint32_t));   // one bin + slack
  LogHistogram wide;
  for (int k = 0; k < binning.bin_count(); ++k) wide.add(binning.lower(k), binning);
  EXPECT_LE(wide.memory_bytes(), sizeof(LogHistogram) + binning.bin_count() * sizeof(std::uint32_t));
}

}  // namespace
}  // namespace talus
