// Tests of CellCounts (docs/architecture.md section 2, "Statistical maps": passages and deposits).
#include "talus/hazard/cell_counts.hpp"

#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

namespace talus {
namespace {

TEST(CellCounts, CountsPerCellFromZero) {
  CellCounts counts(5);
  counts.add(1);
  counts.add(1);
  counts.add(4, 7);
  EXPECT_EQ(counts[0], 0u);
  EXPECT_EQ(counts[1], 2u);
  EXPECT_EQ(counts[4], 7u);
  EXPECT_EQ(counts.size(), 5u);
}

TEST(CellCounts, MergeAddsCellByCell) {
  CellCounts a(3);
  CellCounts b(3);
  a.add(0, 2);
  b.add(0, 3);
  b.add(2, 1);
  a.merge(b);
  EXPECT_EQ(a[0], 5u);
  EXPECT_EQ(a[1], 0u);
  EXPECT_EQ(a[2], 1u);
}

TEST(CellCounts, SaturatesInsteadOfWrapping) {
  constexpr std::uint32_t top = std::numeric_limits<std::uint32_t>::max();
  CellCounts a(1);
  a.add(0, top - 1);
  a.add(0, 5);
  EXPECT_EQ(a[0], top);
  CellCounts b(1);
  b.add(0, 10);
  b.merge(a);
  EXPECT_EQ(b[0], top);
}

TEST(CellCounts, RefusesToMergeAnotherSize) {
  CellCounts a(3);
  EXPECT_THROW(a.merge(CellCounts(4)), std::invalid_argument);
}

}  // namespace
}  // namespace talus
