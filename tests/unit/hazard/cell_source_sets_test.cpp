// Tests of CellSourceSets (docs/hazard-statistics.md, "How `source_count` is gathered"): distinct
// sources per cell in any order of addition, and a union merge that gives the counts of a single
// accumulation however the sources were split.
#include "talus/hazard/cell_source_sets.hpp"

#include <algorithm>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

std::vector<SourceInterval> intervals_of(const CellSourceSets& sets, std::size_t cell) {
  const auto span = sets.intervals(cell);
  return {span.begin(), span.end()};
}

TEST(CellSourceSets, CountsEachSourceOncePerCell) {
  CellSourceSets sets(4);
  for (const std::uint32_t source : {3u, 3u, 4u, 5u, 5u, 9u, 12u, 12u}) sets.add(1, source);
  sets.add(3, 0);
  EXPECT_EQ(sets.count(0), 0u);
  EXPECT_EQ(sets.count(1), 5u);   // 3, 4, 5, 9, 12
  EXPECT_EQ(sets.count(3), 1u);
  EXPECT_EQ(intervals_of(sets, 1), (std::vector<SourceInterval>{{3, 5}, {9, 9}, {12, 12}}));
  EXPECT_TRUE(sets.intervals(2).empty());
  EXPECT_EQ(sets.reached_cells(), 2u);
}

TEST(CellSourceSets, SourcesInAnyOrderGiveTheSameIntervals) {
  std::mt19937_64 random(7);
  std::vector<std::uint32_t> sources;
  for (std::uint32_t s = 0; s < 400; ++s) {
    if (random() % 3 != 0) sources.push_back(s);   // gaps of one and more
  }
  const std::set<std::uint32_t> distinct(sources.begin(), sources.end());
  CellSourceSets sorted(1);
  for (const std::uint32_t s : sources) sorted.add(0, s);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<std::uint32_t> shuffled = sources;
    shuffled.insert(shuffled.end(), sources.begin(), sources.begin() + 50);   // repeats
    std::shuffle(shuffled.begin(), shuffled.end(), random);
    CellSourceSets sets(1);
    for (const std::uint32_t s : shuffled) sets.add(0, s);
    EXPECT_EQ(sets.count(0), distinct.size()) << "trial " << trial;
    EXPECT_EQ(intervals_of(sets, 0), intervals_of(sorted, 0)) << "trial " << trial;
  }
}

TEST(CellSourceSets, FillingTheGapBetweenTwoIntervalsJoinsThem) {
  CellSourceSets sets(1);
  for (const std::uint32_t source : {10u, 11u, 13u, 14u, 12u}) sets.add(0, source);
  EXPECT_EQ(intervals_of(sets, 0), (std::vector<SourceInterval>{{10, 14}}));
  sets.add(0, 8);
  sets.add(0, 9);
  EXPECT_EQ(intervals_of(sets, 0), (std::vector<SourceInterval>{{8, 14}}));
  sets.add(0, 0xffffffffu);
  sets.add(0, 0xfffffffeu);
  EXPECT_EQ(intervals_of(sets, 0), (std::vector<SourceInterval>{{8, 14}, {0xfffffffeu, 0xffffffffu}}));
  EXPECT_EQ(sets.count(0), 9u);
}

// Runs of one source split between threads: the merge is a union, not a sum.
TEST(CellSourceSets, MergeUnitesTheSetsInAnyOrder) {
  constexpr std::size_t kCells = 30;
  std::mt19937_64 random(3);
  // (cell, source) pairs as a run of trajectories would add them: sources rising, cells random.
  std::vector<std::pair<std::size_t, std::uint32_t>> additions;
  for (std::uint32_t source = 0; source < 200; ++source) {
    for (int k = 0; k < 12; ++k) additions.emplace_back(random() % kCells, source);
  }
  CellSourceSets single(kCells);
  for (const auto& [cell, source] : additions) single.add(cell, source);
  for (const std::size_t parts : {std::size_t{2}, std::size_t{5}}) {
    std::vector<CellSourceSets> split(parts, CellSourceSets(kCells));
    for (std::size_t i = 0; i < additions.size(); ++i) {
      split[(i / 7) % parts].add(additions[i].first, additions[i].second);   // chunks of 7 cut the sources
    }
    std::vector<std::size_t> order(parts);
    std::iota(order.begin(), order.end(), 0);
    for (int trial = 0; trial < 3; ++trial) {
      std::shuffle(order.begin(), order.end(), random);
      CellSourceSets merged(kCells);
      for (const std::size_t p : order) merged.merge(split[p]);
      merged.merge(split[order[0]]);   // merging a part again adds nothing
      for (std::size_t cell = 0; cell < kCells; ++cell) {
        EXPECT_EQ(intervals_of(merged, cell), intervals_of(single, cell)) << parts << " parts, cell " << cell;
      }
    }
  }
  std::uint64_t reached = 0;
  for (std::size_t cell = 0; cell < kCells; ++cell) reached += single.count(cell);
  EXPECT_GT(reached, 1000u);
}

TEST(CellSourceSets, RefusesToMergeAnotherSize) {
  CellSourceSets a(3);
  EXPECT_THROW(a.merge(CellSourceSets(4)), std::invalid_argument);
}

}  // namespace
}  // namespace talus
