// Tests of the grid walk under trajectory segments (paper 3.4, "Gathering simulation data").
#include "talus/hazard/segment_cells.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

constexpr int kWidth = 12;
constexpr int kHeight = 9;
using Cell = std::pair<int, int>;   // (col, row)

struct Visit {
  int col, row;
  double t0, t1;
};

std::vector<Visit> walk(double u0, double v0, double u1, double v1) {
  std::vector<Visit> visits;
  walk_segment_cells(u0, v0, u1, v1, kWidth, kHeight,
                     [&](int col, int row, double t0, double t1) { visits.push_back({col, row, t0, t1}); });
  return visits;
}

std::set<Cell> cells_of(const std::vector<Visit>& visits) {
  std::set<Cell> cells;
  for (const Visit& v : visits) cells.insert({v.col, v.row});
  return cells;
}

// Parameters t in [0, 1] with low <= p + t d < high, as an interval with open or closed ends.
struct Interval {
  double low = 0, high = 1;
  bool low_open = false, high_open = false;
  void intersect(double l, bool lo, double h, bool ho) {
    if (l > low || (l == low && lo)) low = l, low_open = lo;
    if (h < high || (h == high && ho)) high = h, high_open = ho;
  }
  bool empty() const { return low > high || (low == high && (low_open || high_open)); }
};

void restrict_axis(Interval& interval, double p, double d, int cell) {
  if (d == 0) {
    if (!(cell <= p && p < cell + 1)) interval.low = 2;   // empty
    return;
  }
  const double a = (cell - p) / d;
  const double b = (cell + 1 - p) / d;
  if (d > 0) interval.intersect(a, false, b, true);    // [a, b)
  else interval.intersect(b, true, a, false);          // (b, a]
}

// Brute force by exact geometry: every grid cell holding a point of the closed segment.
std::set<Cell> exact_cells(double u0, double v0, double u1, double v1) {
  std::set<Cell> cells;
  for (int row = 0; row < kHeight; ++row) {
    for (int col = 0; col < kWidth; ++col) {
      Interval interval;
      restrict_axis(interval, u0, u1 - u0, col);
      restrict_axis(interval, v0, v1 - v0, row);
      if (!interval.empty()) cells.insert({col, row});
    }
  }
  return cells;
}

// Brute force by fine sampling: the cells of 200001 points along the segment.
std::set<Cell> sampled_cells(double u0, double v0, double u1, double v1) {
  constexpr int kSteps = 200000;
  std::set<Cell> cells;
  for (int i = 0; i <= kSteps; ++i) {
    const double t = static_cast<double>(i) / kSteps;
    const double u = u0 + t * (u1 - u0);
    const double v = v0 + t * (v1 - v0);
    if (u >= 0 && v >= 0 && u < kWidth && v < kHeight) cells.insert({static_cast<int>(std::floor(u)), static_cast<int>(std::floor(v))});
  }
  return cells;
}

// Visits are in order along the segment, edge- or corner-adjacent, and tile [t_in, t_out].
void expect_ordered(const std::vector<Visit>& visits) {
  for (std::size_t i = 0; i < visits.size(); ++i) {
    EXPECT_LE(visits[i].t0, visits[i].t1);
    EXPECT_GE(visits[i].t0, 0.0);
    EXPECT_LE(visits[i].t1, 1.0);
    if (i == 0) continue;
    EXPECT_EQ(visits[i].t0, visits[i - 1].t1);
    EXPECT_LE(std::abs(visits[i].col - visits[i - 1].col), 1);
    EXPECT_LE(std::abs(visits[i].row - visits[i - 1].row), 1);
    EXPECT_NE(std::make_pair(visits[i].col, visits[i].row), std::make_pair(visits[i - 1].col, visits[i - 1].row));
  }
}

TEST(SegmentCells, RandomSegmentsCrossExactlyTheCellsOfBruteForce) {
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> u(-3.0, kWidth + 3.0);
  std::uniform_real_distribution<double> v(-3.0, kHeight + 3.0);
  std::uniform_real_distribution<double> shortish(-1.5, 1.5);
  for (int trial = 0; trial < 2000; ++trial) {
    const double u0 = u(random);
    const double v0 = v(random);
    // Long segments across the grid and short ones like trajectory samples.
    const double u1 = trial % 2 ? u(random) : u0 + shortish(random);
    const double v1 = trial % 2 ? v(random) : v0 + shortish(random);
    const std::vector<Visit> visits = walk(u0, v0, u1, v1);
    const std::set<Cell> walked = cells_of(visits);
    EXPECT_EQ(walked.size(), visits.size()) << "a straight segment enters each cell once";
    EXPECT_EQ(walked, exact_cells(u0, v0, u1, v1)) << u0 << "," << v0 << " -> " << u1 << "," << v1;
    const std::set<Cell> sampled = sampled_cells(u0, v0, u1, v1);
    EXPECT_TRUE(std::includes(walked.begin(), walked.end(), sampled.begin(), sampled.end()));
    // Cells the sampling misses are clipped over less than two sampling steps.
    for (const Visit& visit : visits) {
      if (!sampled.count({visit.col, visit.row})) {
        EXPECT_LT(visit.t1 - visit.t0, 2.0 / 200000) << trial;
      }
    }
    expect_ordered(visits);
  }
}

TEST(SegmentCells, SegmentsAlongCellEdges) {
  // Along the vertical edge u = 3, both ways: the cells of column 3 (half-open cells).
  for (const auto& [v0, v1] : {std::pair{1.5, 4.5}, std::pair{4.5, 1.5}, std::pair{1.0, 4.0}, std::pair{4.0, 1.0}}) {
    const std::set<Cell> walked = cells_of(walk(3.0, v0, 3.0, v1));
    EXPECT_EQ(walked, exact_cells(3.0, v0, 3.0, v1));
    EXPECT_EQ(walked, sampled_cells(3.0, v0, 3.0, v1));
    for (const Cell& c : walked) EXPECT_EQ(c.first, 3);
  }
  // Along the horizontal edge v = 2, and along the grid's own outer edges.
  for (const auto& [u0, u1] : {std::pair{0.25, 7.75}, std::pair{7.75, 0.25}}) {
    EXPECT_EQ(cells_of(walk(u0, 2.0, u1, 2.0)), exact_cells(u0, 2.0, u1, 2.0));
    EXPECT_EQ(cells_of(walk(u0, 2.0, u1, 2.0)), sampled_cells(u0, 2.0, u1, 2.0));
    EXPECT_EQ(cells_of(walk(u0, 0.0, u1, 0.0)).size(), 8u);
    EXPECT_TRUE(walk(u0, kHeight, u1, kHeight).empty());   // v = height is outside the last row
  }
}

TEST(SegmentCells, SegmentsThroughCorners) {
  // Diagonals through lattice corners in all four directions, starting and ending at corners
  // or inside cells, and the diagonals of the whole grid.
  const double segments[][4] = {
      {2.5, 3.5, 5.5, 6.5}, {5.5, 6.5, 2.5, 3.5}, {2.5, 6.5, 5.5, 3.5}, {5.5, 3.5, 2.5, 6.5},
      {2.0, 3.0, 5.0, 6.0}, {5.0, 6.0, 2.0, 3.0}, {2.0, 6.0, 5.0, 3.0}, {5.0, 3.0, 2.0, 6.0},
      {0.0, 0.0, 9.0, 9.0}, {9.0, 9.0, 0.0, 0.0}, {0.5, 0.0, 4.5, 8.0}, {11.0, 0.5, 1.0, 5.5},
  };
  for (const auto& s : segments) {
    const std::vector<Visit> visits = walk(s[0], s[1], s[2], s[3]);
    const std::set<Cell> walked = cells_of(visits);
    const std::set<Cell> sampled = sampled_cells(s[0], s[1], s[2], s[3]);
    EXPECT_EQ(walked, exact_cells(s[0], s[1], s[2], s[3])) << s[0] << "," << s[1] << " -> " << s[2] << "," << s[3];
    // Sampling finds a corner's cell only where a sample falls exactly on the corner.
    EXPECT_TRUE(std::includes(walked.begin(), walked.end(), sampled.begin(), sampled.end()));
    expect_ordered(visits);
  }
  // Down-right and up-left (u and v both growing or both shrinking) through corners: the
  // diagonal cells only; the corner belongs to one of them.
  const std::set<Cell> diagonal{{2, 3}, {3, 4}, {4, 5}, {5, 6}};
  EXPECT_EQ(cells_of(walk(2.5, 3.5, 5.5, 6.5)), diagonal);
  EXPECT_EQ(cells_of(walk(5.5, 6.5, 2.5, 3.5)), diagonal);
  EXPECT_EQ(cells_of(walk(2.5, 3.5, 5.5, 6.5)), sampled_cells(2.5, 3.5, 5.5, 6.5));
  // Across the other diagonal each corner point is in a side cell: (3, 4) for the corner
  // (3, 4), in both directions.
  const std::set<Cell> staircase{{2, 4}, {3, 4}, {3, 3}};
  EXPECT_EQ(cells_of(walk(2.5, 4.5, 3.5, 3.5)), staircase);
  EXPECT_EQ(cells_of(walk(3.5, 3.5, 2.5, 4.5)), staircase);
  EXPECT_EQ(cells_of(walk(3.5, 3.5, 2.5, 4.5)), sampled_cells(3.5, 3.5, 2.5, 4.5));
}

TEST(SegmentCells, PointsAndSegmentsOutsideTheGrid) {
  const std::vector<Visit> point = walk(4.25, 5.75, 4.25, 5.75);
  ASSERT_EQ(point.size(), 1u);
  EXPECT_EQ(point[0].col, 4);
  EXPECT_EQ(point[0].row, 5);
  EXPECT_TRUE(walk(-5.0, -5.0, -1.0, 20.0).empty());
  EXPECT_TRUE(walk(0.5, 0.5, 0.5, std::numeric_limits<double>::quiet_NaN()).empty());
  // A very long segment crossing the grid: only the in-grid cells, with their true parameters.
  const std::vector<Visit> far = walk(-1e7, 4.5, 1e7, 4.5);
  ASSERT_EQ(far.size(), static_cast<std::size_t>(kWidth));
  EXPECT_NEAR(far.front().t0, 0.5, 1e-9);
  EXPECT_NEAR(far.back().t1, 0.5 + kWidth / 2e7, 1e-9);
}

TEST(SegmentCells, CellFrameFollowsTheGeotransform) {
  GridSpec spec;
  spec.width = 4;
  spec.height = 3;
  spec.geotransform = {1000.0, 5.0, 0.0, 2000.0, 0.0, -5.0};
  const CellFrame frame(spec);
  EXPECT_DOUBLE_EQ(frame.u(1012.5), 2.5);
  EXPECT_DOUBLE_EQ(frame.v(1990.0), 2.0);   // 10 m south of the top edge: the top of row 2
  EXPECT_TRUE(frame.inside(frame.u(1019.9), frame.v(1985.1)));
  EXPECT_FALSE(frame.inside(frame.u(1020.0), frame.v(1990.0)));   // x at the right edge
  EXPECT_FALSE(frame.inside(frame.u(1010.0), frame.v(1985.0)));   // y at the bottom edge
}

}  // namespace
}  // namespace talus
