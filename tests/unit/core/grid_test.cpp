// Tests of Grid<T>, GridSpec and combine (docs/architecture.md section 1).
#include "talus/core/grid.hpp"

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "talus/core/errors.hpp"
#include "talus/core/grid_spec.hpp"

namespace talus {
namespace {

GridSpec small_spec() {
  GridSpec spec;
  spec.width = 4;
  spec.height = 3;
  spec.geotransform = {500.0, 2.0, 0.0, 900.0, 0.0, -2.5};
  spec.crs_wkt = "LOCAL_CS[\"test\"]";
  spec.nodata = -1.0;
  return spec;
}

TEST(Grid, StoresRowMajorAndFills) {
  Grid<int> grid(small_spec(), 7);
  ASSERT_EQ(grid.size(), 12u);
  EXPECT_EQ(grid.width(), 4);
  EXPECT_EQ(grid.height(), 3);
  EXPECT_EQ(grid.at(3, 2), 7);
  grid.at(1, 2) = 42;
  EXPECT_EQ(grid.index(1, 2), 9u);
  EXPECT_EQ(grid[9], 42);
  EXPECT_EQ(grid.values()[9], 42);
}

TEST(Grid, RefusesAValueCountThatDoesNotMatchTheSpec) {
  EXPECT_THROW(Grid<double>(small_spec(), std::vector<double>(11, 0.0)), GridMismatch);
  EXPECT_NO_THROW(Grid<double>(small_spec(), std::vector<double>(12, 0.0)));
}

TEST(Grid, NodataNonFiniteAndOutsideCellsAreInvalid) {
  Grid<double> grid(small_spec(), 10.0);
  grid.at(0, 0) = -1.0;  // the spec's nodata
  grid.at(1, 0) = std::numeric_limits<double>::quiet_NaN();
  grid.at(2, 0) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(grid.is_valid(0, 0));
  EXPECT_FALSE(grid.is_valid(1, 0));
  EXPECT_FALSE(grid.is_valid(2, 0));
  EXPECT_TRUE(grid.is_valid(3, 0));
  EXPECT_TRUE(grid.is_valid(grid.index(3, 2)));
  EXPECT_FALSE(grid.is_valid(-1, 1));
  EXPECT_FALSE(grid.is_valid(4, 1));
  EXPECT_FALSE(grid.is_valid(0, 3));
}

TEST(GridSpec, NodesAreCellCentresAndColOfInvertsNodeX) {
  const GridSpec spec = small_spec();
  EXPECT_DOUBLE_EQ(spec.node_x(0), 501.0);
  EXPECT_DOUBLE_EQ(spec.node_y(0), 898.75);
  EXPECT_NEAR(spec.col_of(spec.node_x(2.3)), 2.3, 1e-12);
  EXPECT_NEAR(spec.row_of(spec.node_y(1.7)), 1.7, 1e-12);
  EXPECT_DOUBLE_EQ(spec.col_of(500.0), -0.5);  // the raster's west edge
  EXPECT_DOUBLE_EQ(spec.cell_area(), 5.0);
}

TEST(GridSpec, SameGridToleratesRoundingButNotRealDifferences) {
  const GridSpec spec = small_spec();
  GridSpec rounded = spec;
  rounded.geotransform[0] += 1e-12;
  EXPECT_TRUE(spec.same_grid(rounded));
  GridSpec shifted = spec;
  shifted.geotransform[3] += 0.5;
  EXPECT_FALSE(spec.same_grid(shifted));
}

TEST(Grid, CombineAppliesTheFunctionCellByCell) {
  Grid<double> a(small_spec(), 2.0);
  Grid<int> b(small_spec(), 3);
  a.at(2, 1) = 5.0;
  const auto sum = combine(a, b, [](double u, int v) { return u * v; }, "test");
  EXPECT_TRUE(sum.spec().same_grid(a.spec()));
  EXPECT_EQ(sum.at(0, 0), 6.0);
  EXPECT_EQ(sum.at(2, 1), 15.0);
}

TEST(Grid, CombineRefusesGridsWithDifferentSpecs) {
  const GridSpec spec = small_spec();
  GridSpec wider = spec;
  wider.width = 5;
  GridSpec taller = spec;
  taller.height = 4;
  GridSpec moved = spec;
  moved.geotransform[0] += 2.0;
  GridSpec coarser = spec;
  coarser.geotransform[5] = -5.0;
  GridSpec other_crs = spec;
  other_crs.crs_wkt = "EPSG:2154";
  const Grid<double> a(spec, 1.0);
  const auto add = [](double u, double v) { return u + v; };
  for (const GridSpec& other : {wider, taller, moved, coarser, other_crs}) {
    EXPECT_THROW(combine(a, Grid<double>(other, 1.0), add, "test"), GridMismatch);
  }
  try {
    combine(a, Grid<double>(wider, 1.0), add, "slope and lithology");
    FAIL() << "combine accepted a grid of another size";
  } catch (const GridMismatch& error) {
    EXPECT_NE(std::string(error.what()).find("slope and lithology"), std::string::npos);
  }
}

}  // namespace
}  // namespace talus

namespace talus {
namespace {

// Issue 19, item 4: a window keeps the whole grid's geotransform, so points fall in the same
// cells by the same rounding; GDAL sees its own origin.
TEST(GridWindow, MapsPointsToTheSameCellsAsTheWholeGrid) {
  GridSpec whole = small_spec();
  whole.width = 400;
  whole.height = 300;
  const GridSpec window = whole.window(123, 45, 50, 60);
  EXPECT_TRUE(window.is_window());
  EXPECT_TRUE(window.whole().same_grid(whole));
  EXPECT_FALSE(window.same_grid(whole));
  for (const double x : {500.0 + 123 * 2.0, 747.3, 500.0 + 172.75 * 2.0}) {
    EXPECT_EQ(window.col_of(x), whole.col_of(x) - 123) << x;
  }
  for (const double y : {900.0 - 45 * 2.5, 770.123456789}) EXPECT_EQ(window.row_of(y), whole.row_of(y) - 45) << y;
  EXPECT_EQ(window.node_x(0), whole.node_x(123));
  EXPECT_EQ(window.node_y(59), whole.node_y(104));
  EXPECT_EQ(window.whole_index(0), whole.width * 45u + 123u);
  EXPECT_EQ(window.whole_index(50 * 2 + 7), whole.width * 47u + 130u);
  const auto gt = window.own_geotransform();
  EXPECT_EQ(gt[0], 500.0 + 123 * 2.0);
  EXPECT_EQ(gt[3], 900.0 - 45 * 2.5);
  EXPECT_THROW(whole.window(390, 0, 20, 10), std::invalid_argument);
  EXPECT_THROW(window.window(0, 0, 1, 1), std::invalid_argument);
}

}  // namespace
}  // namespace talus
