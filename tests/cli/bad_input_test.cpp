// Bad inputs (docs/architecture.md section 3): exit code 2, one line `talus: error: ...` naming the
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
    // Terrain no DEM of the Earth has (issue 18, item 2).
    RasterFixture tiny_cells;
    tiny_cells.cell = 1e-142;
    write_raster(inputs_ / "dem_tiny_cells.tif", tiny_cells);
    RasterFixture huge_cells;
    huge_cells.cell = 50000.0;
    write_raster(inputs_ / "dem_huge_cells.tif", huge_cells);
    RasterFixture far_corner;
    far_corner.x0 = 3e12;
    write_raster(inputs_ / "dem_far_corner.tif", far_corner);
    RasterFixture impossible;
    impossible.value = [](int c, int r) { return c < 5 ? 1e12 * (r + 1) : 1000.0 - r; };
    write_raster(inputs_ / "dem_impossible_elevations.tif", impossible);
    RasterFixture feet_like;  // elevations of a DEM in millimetres
    feet_like.value = [](int, int r) { return 1.5e6 - 1000.0 * r; };
    write_raster(inputs_ / "dem_in_millimetres.tif", feet_like);
    // A header of 200000 x 200000 cells (40 billion: 320 GB of elevations) over a real file.
    std::ofstream(inputs_ / "dem_huge_header.vrt")
        << "<VRTDataset rasterXSize=\"200000\" rasterYSize=\"200000\"><SRS>EPSG:32632</SRS>"
           "<GeoTransform>500000, 1, 0, 5200000, 0, -1</GeoTransform><VRTRasterBand dataType=\"Float32\" band=\"1\">"
           "<SimpleSource><SourceFilename relativeToVRT=\"1\">dem.tif</SourceFilename><SourceBand>1</SourceBand>"
           "</SimpleSource></VRTRasterBand></VRTDataset>\n";
    // Release points 2^32 + 100 cells east of the DEM's corner (10 m cells), and far beyond.
    test::write_vector(inputs_ / "release_wrapping.gpkg", "EPSG:32632", {{"POINT(42950173965 5199850)", 0}}, false);
    test::write_vector(inputs_ / "release_1e300.gpkg", "EPSG:32632", {{"POINT(1e300 5199850)", 0}}, false);
    test::write_vector(inputs_ / "release_west.gpkg", "EPSG:32632", {{"POINT(-42949171955 5199850)", 0}}, false);
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
                 {(test::data_dir() / "fluchthorn_bad_crs/fluchthorn.tif").string()},
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
        BadInput{"bad_crs_option", {"dem.tif", "--crs", "EPSG:999999"}, "--crs", "not a CRS"},
        BadInput{"dem_tiny_cells", {"dem_tiny_cells.tif"}, "dem_tiny_cells.tif", "expected 0.01-10000 m"},
        BadInput{"dem_huge_cells", {"dem_huge_cells.tif"}, "dem_huge_cells.tif", "expected 0.01-10000 m"},
        BadInput{"dem_far_corner", {"dem_far_corner.tif"}, "dem_far_corner.tif", "off any projected CRS"},
        BadInput{"dem_impossible_elevations", {"dem_impossible_elevations.tif"}, "dem_impossible_elevations.tif",
                 "impossible on Earth"},
        BadInput{"dem_in_millimetres", {"dem_in_millimetres.tif"}, "dem_in_millimetres.tif", "impossible on Earth"},
        BadInput{"dem_huge_header", {"dem_huge_header.vrt"}, "dem_huge_header.vrt", "more than this machine's"},
        BadInput{"release_wrapping_column", {"dem.tif", "--release", "release_wrapping.gpkg"}, "release_wrapping.gpkg",
                 "outside the DEM"},
        BadInput{"release_far_beyond", {"dem.tif", "--release", "release_1e300.gpkg"}, "release_1e300.gpkg",
                 "outside the DEM"},
        BadInput{"release_wrapping_west", {"dem.tif", "--release", "release_west.gpkg"}, "release_west.gpkg",
                 "outside the DEM"}),
    [](const ::testing::TestParamInfo<BadInput>& case_info) { return case_info.param.name; });

// ESRI's usual nodata, -3.4028235e38, undeclared in the file across the path of the rocks: once
// `talus rockfall` never finished here; the cells are now nodata and the run ends (issue 18).
TEST(ImpossibleElevations, AnUndeclaredNodataValueBecomesNodataAndTheRunEnds) {
  const auto work = test::fresh_folder("impossible_elevations_run");
  RasterFixture slope;
  slope.value = [](int c, int r) {
    return r >= 15 && r < 18 && c > 10 && c < 30 ? -3.4028234663852886e38 : 1000.0 - 8.0 * r;  // -FLT_MAX
  };
  write_raster(work / "dem.tif", slope);
  test::write_vector(work / "release.gpkg", "EPSG:32632", {{"POINT(500205 5199985)", 0}}, false);
  const auto result = test::run_talus({"rockfall", "--dem", (work / "dem.tif").string(), "--release",
                                       (work / "release.gpkg").string(), "--out", (work / "out").string(), "--runs",
                                       "4", "--intensity", "none"},
                                      work);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("note: 57 cells of elevation -3.40282347e+38 m (impossible on Earth, an undeclared nodata "
                            "value) taken as nodata"),
            std::string::npos)
      << result.out;
  const std::vector<float> passages = test::read_band(work / "out" / "passages.tif");
  EXPECT_EQ(passages[16 * 40 + 20], -9999.0f);  // nodata in the layers too
}

TEST(Usage, UnknownOptionIsExitTwo) {
  const auto work = test::fresh_folder("usage_unknown_option");
  const auto result = test::run_talus({"info", "--no-such-option"}, work);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.err.rfind("talus: error: ", 0), 0u) << result.err;
}

}  // namespace
}  // namespace talus
