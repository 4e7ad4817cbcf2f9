// Tests of the counter-based random numbers (docs/architecture.md section 3: same seed, same layers).
#include "talus/core/counter_random.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

constexpr int kSamples = 200000;

std::vector<std::uint64_t> draw_bits(CounterRandom random, int count) {
  std::vector<std::uint64_t> bits;
  for (int k = 0; k < count; ++k) bits.push_back(random.next_bits());
  return bits;
}

int count_equal(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) {
  int equal = 0;
  for (std::size_t k = 0; k < a.size(); ++k) equal += a[k] == b[k] ? 1 : 0;
  return equal;
}

TEST(CounterRandom, SameSeedSourceAndRunGiveTheSameSequence) {
  CounterRandom first(2024, 17, 5);
  CounterRandom second(2024, 17, 5);
  for (int k = 0; k < 1000; ++k) {
    ASSERT_EQ(first.next_bits(), second.next_bits());
    ASSERT_EQ(first.uniform(), second.uniform());
    ASSERT_EQ(first.normal(), second.normal());
  }
  EXPECT_EQ(first.draws(), second.draws());
}

TEST(CounterRandom, EachDrawIsThePureHashOfItsCounter) {
  CounterRandom random(9, 8, 7);
  for (std::uint64_t counter = 0; counter < 100; ++counter) {
    EXPECT_EQ(random.draws(), counter);
    EXPECT_EQ(random.next_bits(), counter_hash(9, 8, 7, counter));
  }
}

TEST(CounterRandom, DifferentRunSourceOrSeedGiveDifferentSequences) {
  const auto reference = draw_bits(CounterRandom(2024, 17, 5), 1000);
  EXPECT_EQ(count_equal(reference, draw_bits(CounterRandom(2024, 17, 6), 1000)), 0);
  EXPECT_EQ(count_equal(reference, draw_bits(CounterRandom(2024, 18, 5), 1000)), 0);
  EXPECT_EQ(count_equal(reference, draw_bits(CounterRandom(2025, 17, 5), 1000)), 0);
  // Swapped words are other streams too.
  EXPECT_EQ(count_equal(reference, draw_bits(CounterRandom(2024, 5, 17), 1000)), 0);
}

// Uniform [0, 1): mean 1/2 and variance 1/12, within five standard errors of N samples.
TEST(CounterRandom, UniformIsInRangeWithTheRightMeanAndVariance) {
  CounterRandom random(1, 2, 3);
  double sum = 0, sum_sq = 0;
  for (int k = 0; k < kSamples; ++k) {
    const double u = random.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum_sq += u * u;
  }
  const double n = kSamples;
  const double mean = sum / n;
  const double variance = sum_sq / n - mean * mean;
  EXPECT_NEAR(mean, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
  // sd of a sample variance: sqrt((mu4 - sigma^4) / n) with mu4 = 1/80, sigma^4 = 1/144.
  EXPECT_NEAR(variance, 1.0 / 12.0, 5.0 * std::sqrt((1.0 / 80.0 - 1.0 / 144.0) / n));
}

TEST(CounterRandom, UniformOnAnIntervalStaysInsideIt) {
  CounterRandom random(4, 5, 6);
  double sum = 0;
  for (int k = 0; k < kSamples; ++k) {
    const double u = random.uniform(-3.0, 5.0);
    ASSERT_GE(u, -3.0);
    ASSERT_LT(u, 5.0);
    sum += u;
  }
  EXPECT_NEAR(sum / kSamples, 1.0, 5.0 * 8.0 * std::sqrt(1.0 / 12.0 / kSamples));
}

// Standard normal: mean 0 (se 1/sqrt(N)), variance 1 (se sqrt(2/N)), and 68.27 % within one sd.
TEST(CounterRandom, NormalHasZeroMeanUnitVarianceAndTheRightShape) {
  CounterRandom random(11, 0, 42);
  double sum = 0, sum_sq = 0;
  int within_one = 0;
  for (int k = 0; k < kSamples; ++k) {
    const double z = random.normal();
    ASSERT_TRUE(std::isfinite(z));
    sum += z;
    sum_sq += z * z;
    within_one += std::abs(z) < 1.0 ? 1 : 0;
  }
  const double n = kSamples;
  const double mean = sum / n;
  const double variance = sum_sq / n - mean * mean;
  EXPECT_NEAR(mean, 0.0, 5.0 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(variance), 1.0, 0.5 * 5.0 * std::sqrt(2.0 / n));
  const double p = 0.682689;
  EXPECT_NEAR(within_one / n, p, 5.0 * std::sqrt(p * (1.0 - p) / n));
}

}  // namespace
}  // namespace talus
