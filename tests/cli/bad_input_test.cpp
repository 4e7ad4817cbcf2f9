// Bad inputs (DESIGN.md section 3): exit code 2, one line `talus: error: ...` naming the
// file and the problem, and nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

using test::RasterFixture;

struct BadInput {
  std::string name;                    // test name
  std::vector<std::string> arguments;  // talus info arguments, paths relative to the inputs folder
  std::string file;                    // what the message must name
  std::string problem;                 // a phrase of the message
};

// Names the case in test listings instead of dumping its bytes.
void PrintTo(const BadInput& bad, std::ostream* os) { *os << bad.name; }

class BadInputs : public ::testing::TestWithParam<BadInput> {
 protected:
  static void SetUpTestSuite() {
    inputs_ = test::fresh_folder("bad_inputs");
    write_raster(inputs_ / "dem.tif", RasterFixture{});  // UTM 32N, 400 x 300 m
    RasterFixture no_crs;
    no_crs.crs.clear();
    write_raster(inputs_ / "dem_without_crs.tif", no_crs);
    RasterFixture feet;
    feet.unit = "ft";
    write_raster(inputs_ / "dem_in_feet.tif", feet);
    std::ofstream(inputs_ / "not_a_raster.tif") << "this is a text file, not a GeoTIFF\n";
    RasterFixture far_away;
    far_away.x0 = 700000.0;
    far_away.integer = true;
    far_away.value = [](int, int) { return 4.0; };
    write_raster(inputs_ / "lithology_elsewhere.tif", far_away);
    RasterFixture unknown;
    unknown.integer = true;
    unknown.value = [](int c, int) { return c < 3 ? 99.0 : 4.0; };
    write_raster(inputs_ / "lithology_unknown.tif", unknown);
    test::write_vector(inputs_ / "release_outside.gpkg", "EPSG:32632", {{"POINT(510000 5210000)", 0}}, false);
    test::write_vector(inputs_ / "release_empty.gpkg", "EPSG:32632", {}, false);
  }
  static void TearDownTestSuite() { std::filesystem::remove_all(inputs_); }
  static std::filesystem::path inputs_;
};
std::filesystem::path BadInputs::inputs_;

TEST_P(BadInputs, ExitTwoWithOneLineAndWriteNothing) {
  const BadInput& bad = GetParam();
  const auto work = test::fresh_folder("bad_input_run_" + bad.name);
  std::vector<std::string> arguments = {"info"};
  for (const auto& a : bad.arguments) {
    const bool is_path = a.find('.') != std::string::npos && a.rfind("--", 0) != 0;
    arguments.push_back(is_path && a.find("/") == std::string::npos ? (inputs_ / a).string() : a);
  }
  const auto result = test::run_talus(arguments, work);
  EXPECT_EQ(result.exit_code, 2) << result.err;
  ASSERT_FALSE(result.err.empty());
  EXPECT_EQ(result.err.rfind("talus: error: ", 0), 0u) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_NE(result.err.find(bad.file), std::string::npos) << result.err;
  EXPECT_NE(result.err.find(bad.problem), std::string::npos) << result.err;
  EXPECT_TRUE(std::filesystem::is_empty(work)) << "something was written";
}

INSTANTIATE_TEST_SUITE_P(
    Info, BadInputs,
    ::testing::Values(
        BadInput{"missing_file", {"missing.tif"}, "missing.tif", "file not found"},
        BadInput{"not_a_raster", {"not_a_raster.tif"}, "not_a_raster.tif", "not a raster"},
        BadInput{"dem_without_crs", {"dem_without_crs.tif"}, "dem_without_crs.tif", "has no CRS"},
        BadInput{"crs_contradicts_coordinates",
                 {(test::shared_dir() / "data/fluchthorn_bad_crs/fluchthorn.tif").string()},
                 "fluchthorn.tif",
                 "coordinates"},
        BadInput{"lithology_not_overlapping", {"dem.tif", "--lithology", "lithology_elsewhere.tif"},
                 "lithology_elsewhere.tif", "does not overlap the DEM"},
        BadInput{"unknown_lithology_class", {"dem.tif", "--lithology", "lithology_unknown.tif"},
                 "lithology_unknown.tif", "99"},
        BadInput{"vertical_unit_not_metres", {"dem_in_feet.tif"}, "dem_in_feet.tif", "not metres"},
        BadInput{"release_outside_dem", {"dem.tif", "--release", "release_outside.gpkg"}, "release_outside.gpkg",
                 "outside the DEM"},
        BadInput{"empty_release", {"dem.tif", "--release", "release_empty.gpkg"}, "release_empty.gpkg",
                 "empty release"},
        BadInput{"bad_crs_option", {"dem.tif", "--crs", "EPSG:999999"}, "--crs", "not a CRS"}),
    [](const ::testing::TestParamInfo<BadInput>& case_info) { return case_info.param.name; });

TEST(Usage, UnknownOptionIsExitTwo) {
  const auto work = test::fresh_folder("usage_unknown_option");
  const auto result = test::run_talus({"info", "--no-such-option"}, work);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.err.rfind("talus: error: ", 0), 0u) << result.err;
}

}  // namespace
}  // namespace talus
