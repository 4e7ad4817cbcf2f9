// Tests of CellMaxima (docs/architecture.md section 2, "Statistical maps": maximal energy and velocity).
#include "talus/hazard/cell_maxima.hpp"

#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

TEST(CellMaxima, KeepsTheLargestValueAndStartsAtZero) {
  CellMaxima maxima(3);
  maxima.add(1, 2.5);
  maxima.add(1, 7.25);
  maxima.add(1, 3.0);
  maxima.add(2, -4.0);
  maxima.add(2, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(maxima[0], 0.0f);
  EXPECT_EQ(maxima[1], 7.25f);
  EXPECT_EQ(maxima[2], 0.0f);
}

TEST(CellMaxima, MergeInAnyOrderEqualsOneAccumulation) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> value(0.0, 1e6);
  std::uniform_int_distribution<std::size_t> cell(0, 9);
  CellMaxima single(10);
  std::vector<CellMaxima> parts(4, CellMaxima(10));
  for (int k = 0; k < 400; ++k) {
    const std::size_t c = cell(random);
    const double v = value(random);
    single.add(c, v);
    parts[static_cast<std::size_t>(k) % parts.size()].add(c, v);
  }
  CellMaxima forward(10);
  for (const CellMaxima& part : parts) forward.merge(part);
  CellMaxima backward(10);
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) backward.merge(*it);
  for (std::size_t c = 0; c < 10; ++c) {
    EXPECT_EQ(forward[c], single[c]);
    EXPECT_EQ(backward[c], single[c]);
  }
}

TEST(CellMaxima, RefusesToMergeAnotherSize) {
  CellMaxima a(3);
  EXPECT_THROW(a.merge(CellMaxima(2)), std::invalid_argument);
}

}  // namespace
}  // namespace talus
