// Tests of ZeroedVector, the lazily zeroed storage of the per-cell statistics (docs/architecture.md
// section 2, "Statistical maps").
#include "talus/hazard/zeroed_vector.hpp"

#include <cstdint>

#include <gtest/gtest.h>

namespace talus {
namespace {

TEST(ZeroedVector, StartsAtZeroAndCopiesValues) {
  ZeroedVector<std::int64_t> values(1 << 20);   // large enough for calloc to map fresh pages
  for (std::size_t i = 0; i < values.size(); i += 4099) EXPECT_EQ(values[i], 0);
  values[12345] = -7;
  const ZeroedVector<std::int64_t> copy = values;
  EXPECT_EQ(copy[12345], -7);
  EXPECT_EQ(copy[12346], 0);
  const ZeroedVector<float> floats(100);
  for (const float v : floats) EXPECT_EQ(v, 0.0f);
}

}  // namespace
}  // namespace talus
