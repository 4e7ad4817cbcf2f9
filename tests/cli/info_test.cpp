// `talus info` on real scenes: the sample scene and the Norwegian forest data (issue 2,
// "Done when").
#include <gtest/gtest.h>

#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "missing '" << part << "' in:\n" << text;
}

TEST(Info, SummarisesTheSampleScene) {
  const auto work = test::fresh_folder("info_sample");
  const auto sample = test::source_dir() / "sample_dem";
  const auto result = test::run_talus({"info", (sample / "dem.tif").string(), "--lithology", (sample / "lithology.tif").string(),
                                       "--vegetation", (sample / "vegetation.tif").string(), "--release",
                                       (sample / "rockfall_release.gpkg").string()},
                                      work);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  expect_contains(result.out, "260 x 400 cells of 5 x 5 m (1300 x 2000 m)");
  expect_contains(result.out, "EPSG:31287");
  expect_contains(result.out, "x 255302.083 .. 256602.083 m, y 378605.994 .. 380605.994 m");
  expect_contains(result.out, "6 bedrock");
  expect_contains(result.out, "4 dense forest");
  expect_contains(result.out, "points     260");
  expect_contains(result.out, "62 DEM cells are nodata");
  expect_contains(result.out, "Problems     none");
  EXPECT_TRUE(std::filesystem::is_empty(work));
}

TEST(Info, SummarisesTheMudflowReleasePolygon) {
  const auto work = test::fresh_folder("info_sample_mudflow");
  const auto sample = test::source_dir() / "sample_dem";
  const auto result =
      test::run_talus({"info", (sample / "dem.tif").string(), "--release", (sample / "mudflow_release.gpkg").string()}, work);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  expect_contains(result.out, "depth 1.8 .. 1.8 m");
  // Issue 37, item 4: the convention a mud flow reads the depths with, and both volumes.
  expect_contains(result.out, "mud flow   depths read as thickness normal to the ground (auto: depths given as "
                              "positive values or attributes): 17");
  expect_contains(result.out, "as vertical depths they would give 14445 m3");
  expect_contains(result.out, "lithology: none given; default class 4");
}

TEST(Info, SummarisesTheNorwegianForestWithAContinuousVegetationRaster) {
  const auto work = test::fresh_folder("info_norway");
  const auto data = test::data_dir() / "norway_forest";
  const auto result = test::run_talus({"info", (data / "dem_5m_sn1.asc").string(), "--vegetation", (data / "nD.asc").string(),
                                       "--release", (data / "rel_sn1.asc").string(), "--crs", "EPSG:25833"},
                                      work);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  expect_contains(result.out, "354 x 354 cells of 5 x 5 m");
  expect_contains(result.out, "ETRS89 / UTM zone 33N (EPSG:25833)");
  expect_contains(result.out, "continuous deperdition coefficients");
  expect_contains(result.out, "deperdition coefficient 0 .. 0.04 1/m");
  expect_contains(result.out, "cells of elevation 0 m around the border taken as nodata");
  expect_contains(result.out, "elevation  109.4 .. 942.8 m");
}

}  // namespace
}  // namespace talus
