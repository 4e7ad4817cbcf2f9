// The rock-fall attributes of release features (issue 16): values read from points and
// polygons, NULL and missing fields falling back to the run's, sizes given as "A,B,C" text,
// a CSV through an OGR VRT (every field a text) as docs/inputs.md makes it, and mud flow (no
// run rock) not reading them at all.
#include <gtest/gtest.h>

#include <gdal_priv.h>

#include <array>
#include <fstream>
#include <functional>
#include <numbers>
#include <optional>

#include "raster_fixtures.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/dem_reader.hpp"
#include "talus/gis/release_reader.hpp"
#include "test_paths.hpp"

namespace talus::gis {
namespace {

using test::LayerFeature;
using test::LayerField;

// The fields in the spellings a user may give them (matched case-insensitively).
const std::vector<LayerField> kFields = {{"Shape", true},  {"BLOCK_SIZE", true}, {"density", false},
                                         {"mass", false},  {"vx", false},        {"vy", false},
                                         {"vz", false},    {"Release_Height", false}};

// Every field set: a 2 x 1 x 0.5 m box of 3000 kg/m3 with the given velocity and height.
void expect_box(const ReleaseConditions& c, const std::array<double, 3>& velocity, double release_height) {
  ASSERT_TRUE(c.shape && c.axes && c.density && c.velocity && c.release_height);
  EXPECT_EQ(*c.shape, BlockShape::box);
  EXPECT_EQ(*c.axes, (std::array<double, 3>{2.0, 1.0, 0.5}));
  EXPECT_EQ(*c.density, 3000.0);
  EXPECT_EQ(*c.velocity, velocity);
  EXPECT_EQ(*c.release_height, release_height);
}

class ReleaseAttributes : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = test::fresh_folder("release_attributes");
    write_raster(folder_ / "dem.tif", test::RasterFixture{});  // 400 x 300 m from (500000, 5200000), 10 m cells
    dem_ = read_dem(folder_ / "dem.tif", CrsOption{}).elevation;
    run_rock_.shape = BlockShape::sphere;
    run_rock_.axes = Eigen::Vector3d::Constant(0.8);
    run_rock_.density = 2600.0;
  }
  ReleaseSet read(const std::string& file, const std::vector<LayerFeature>& features) {
    test::write_layer(folder_ / file, "EPSG:32632", kFields, features);
    return read_release(folder_ / file, dem_, CrsOption{}, run_rock_);
  }
  std::filesystem::path folder_;
  Grid<double> dem_;
  Rock run_rock_;
};

TEST_F(ReleaseAttributes, ReadsEveryFieldOfAPoint) {
  const ReleaseSet release =
      read("full.gpkg", {{"POINT(500105 5199895)", {"box", "2,1,0.5", "3000", std::nullopt, "1.5", "-2", "0.25", "3"}}});
  ASSERT_EQ(release.points.size(), 1u);
  expect_box(release.points[0].conditions, {1.5, -2.0, 0.25}, 3.0);
}

TEST_F(ReleaseAttributes, NullAndMissingFieldsKeepTheRunsValues) {
  const ReleaseSet release = read("nulls.gpkg", {{"POINT(500105 5199895)", std::vector<std::optional<std::string>>(8)},
                                                 {"POINT(500205 5199895)", {}},
                                                 {"POINT(500305 5199895)", {std::nullopt, "1.2", std::nullopt, std::nullopt,
                                                                             std::nullopt, "4"}}});
  ASSERT_EQ(release.points.size(), 3u);
  EXPECT_TRUE(release.points[0].conditions.empty());
  EXPECT_TRUE(release.points[1].conditions.empty());
  const ReleaseConditions& c = release.points[2].conditions;
  EXPECT_FALSE(c.shape);
  EXPECT_FALSE(c.density);
  EXPECT_FALSE(c.release_height);
  ASSERT_TRUE(c.axes && c.velocity);
  EXPECT_EQ(*c.axes, (std::array<double, 3>{1.2, 1.2, 1.2}));       // one text number: a diameter
  EXPECT_EQ(*c.velocity, (std::array<double, 3>{0.0, 4.0, 0.0}));  // vy alone: vx = vz = 0
}

TEST_F(ReleaseAttributes, AMassGivesTheDensityOfTheFeaturesRock) {
  // A 2 x 1 x 0.5 m ellipsoid of 1000 kg, and the run's 0.8 m sphere of 500 kg.
  const ReleaseSet release =
      read("mass.gpkg", {{"POINT(500105 5199895)", {"ellipsoid", " 2, 1 ,0.5 ", std::nullopt, "1000"}},
                         {"POINT(500205 5199895)", {std::nullopt, std::nullopt, std::nullopt, "500"}}});
  ASSERT_EQ(release.points.size(), 2u);
  ASSERT_TRUE(release.points[0].conditions.density && release.points[1].conditions.density);
  const double ellipsoid = 4.0 / 3.0 * std::numbers::pi * 1.0 * 0.5 * 0.25;
  const double sphere = 4.0 / 3.0 * std::numbers::pi * 0.4 * 0.4 * 0.4;
  EXPECT_NEAR(*release.points[0].conditions.density, 1000.0 / ellipsoid, 1e-9);
  EXPECT_NEAR(*release.points[1].conditions.density, 500.0 / sphere, 1e-9);
  EXPECT_FALSE(release.points[1].conditions.shape);
}

TEST_F(ReleaseAttributes, EachPolygonCellTakesItsPolygonsConditions) {
  const ReleaseSet release =
      read("polygons.gpkg",
           {{"POLYGON((500000 5200000,500100 5200000,500100 5199900,500000 5199900,500000 5200000))",
             {std::nullopt, std::nullopt, std::nullopt, std::nullopt, "5"}},
            {"POLYGON((500200 5200000,500300 5200000,500300 5199900,500200 5199900,500200 5200000))", {}}});
  EXPECT_EQ(release.cell_count(), 200u);
  EXPECT_EQ(release.depth.at(5, 5), 1.0f);
  EXPECT_EQ(release.depth.at(25, 5), 1.0f);
  const ReleaseConditions first = release.cell_conditions(5, 5);
  ASSERT_TRUE(first.velocity);
  EXPECT_EQ(*first.velocity, (std::array<double, 3>{5.0, 0.0, 0.0}));
  EXPECT_TRUE(release.cell_conditions(25, 5).empty());
  EXPECT_TRUE(release.cell_conditions(15, 5).empty());  // between the polygons
}

TEST_F(ReleaseAttributes, MudFlowDoesNotReadThem) {
  test::write_layer(folder_ / "mud.gpkg", "EPSG:32632", kFields, {{"POINT(500105 5199895)", {"cube", "-1"}}});
  const ReleaseSet release = read_release(folder_ / "mud.gpkg", dem_, CrsOption{});
  ASSERT_EQ(release.points.size(), 1u);
  EXPECT_TRUE(release.points[0].conditions.empty());
  EXPECT_THROW(read_release(folder_ / "mud.gpkg", dem_, CrsOption{}, run_rock_), InputError);
}

// The docs' recipe: a CSV of x, y and the attributes, read through an OGR VRT; every field is
// text there and an empty cell is an empty text, which keeps the run's value.
TEST_F(ReleaseAttributes, ReadsTheCsvAndVrtOfTheDocs) {
  std::ofstream(folder_ / "blocks.csv") << "x,y,shape,block_size,density,mass,vx,vy,vz,release_height\n"
                                           "500105,5199895,box,\"2,1,0.5\",3000,,2,-1,0,1.5\n"
                                           "500205,5199895,,,,,,,,\n";
  std::ofstream(folder_ / "blocks.vrt")
      << "<OGRVRTDataSource>\n  <OGRVRTLayer name=\"blocks\">\n    <SrcDataSource relativeToVRT=\"1\">blocks.csv</SrcDataSource>\n"
         "    <GeometryType>wkbPoint</GeometryType>\n    <LayerSRS>EPSG:32632</LayerSRS>\n"
         "    <GeometryField encoding=\"PointFromColumns\" x=\"x\" y=\"y\"/>\n  </OGRVRTLayer>\n</OGRVRTDataSource>\n";
  const ReleaseSet release = read_release(folder_ / "blocks.vrt", dem_, CrsOption{}, run_rock_);
  ASSERT_EQ(release.points.size(), 2u);
  expect_box(release.points[0].conditions, {2.0, -1.0, 0.0}, 1.5);
  EXPECT_TRUE(release.points[1].conditions.empty());
}

// A release raster on the DEM's grid: band 1 the release cells (1), then one band per
// attribute with the given description and a value per cell ((col, row) -> value; -9999 nodata).
struct AttributeBandValues {
  std::string description;
  std::function<double(int, int)> value;
};

void write_release_raster(const std::filesystem::path& path, const std::function<double(int, int)>& cells,
                          const std::vector<AttributeBandValues>& bands) {
  GDALAllRegister();
  const test::RasterFixture grid;
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDatasetUniquePtr data(driver->Create(path.c_str(), grid.width, grid.height, static_cast<int>(bands.size()) + 1,
                                           GDT_Float32, nullptr));
  double transform[6] = {grid.x0, grid.cell, 0.0, grid.y0, 0.0, -grid.cell};
  data->SetGeoTransform(transform);
  OGRSpatialReference srs;
  srs.SetFromUserInput(grid.crs.c_str());
  data->SetSpatialRef(&srs);
  for (int b = 0; b <= static_cast<int>(bands.size()); ++b) {
    GDALRasterBand* band = data->GetRasterBand(b + 1);
    band->SetNoDataValue(-9999.0);
    if (b > 0) band->SetDescription(bands[static_cast<std::size_t>(b - 1)].description.c_str());
    std::vector<float> values(static_cast<std::size_t>(grid.width * grid.height));
    for (int row = 0; row < grid.height; ++row) {
      for (int col = 0; col < grid.width; ++col) {
        values[static_cast<std::size_t>(row * grid.width + col)] =
            static_cast<float>(b == 0 ? cells(col, row) : bands[static_cast<std::size_t>(b - 1)].value(col, row));
      }
    }
    ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, grid.width, grid.height, values.data(), grid.width, grid.height,
                             GDT_Float32, 0, 0),
              CE_None);
  }
}

// Two release cells, (5, 5) and (6, 5); the attribute bands give (5, 5) a box of 2 m thrown at
// 3 m/s east and leave (6, 5) with nodata, which keeps the run's rock; a cell outside the release
// may hold anything.
TEST_F(ReleaseAttributes, RasterBandsGiveEachReleaseCellItsConditions) {
  const auto cells = [](int col, int row) { return row == 5 && (col == 5 || col == 6) ? 1.0 : 0.0; };
  const auto at_first = [](double value) {
    return [value](int col, int row) { return col == 5 && row == 5 ? value : (col == 6 && row == 5 ? -9999.0 : -1.0); };
  };
  write_release_raster(folder_ / "release.tif", cells,
                       {{"shape", at_first(3.0)}, {"Block_Size", at_first(2.0)}, {"vx", at_first(3.0)}});
  const ReleaseSet release = read_release(folder_ / "release.tif", dem_, CrsOption{}, run_rock_);
  ASSERT_EQ(release.cell_count(), 2u);
  const ReleaseConditions first = release.cell_conditions(5, 5);
  ASSERT_TRUE(first.shape && first.axes && first.velocity);
  EXPECT_EQ(*first.shape, BlockShape::box);
  EXPECT_EQ(*first.axes, (std::array<double, 3>{2.0, 2.0, 2.0}));
  EXPECT_EQ(*first.velocity, (std::array<double, 3>{3.0, 0.0, 0.0}));
  EXPECT_FALSE(first.density || first.release_height);
  EXPECT_TRUE(release.cell_conditions(6, 5).empty());
  // Mud flow (no run rock) reads band 1 alone.
  EXPECT_EQ(read_release(folder_ / "release.tif", dem_, CrsOption{}).condition_sets.size(), 0u);
}

TEST_F(ReleaseAttributes, BadRasterBandsAreRefusedNamingTheBandOrTheCell) {
  const auto cells = [](int col, int row) { return row == 5 && col == 5 ? 1.0 : 0.0; };
  const auto everywhere = [](double value) { return [value](int, int) { return value; }; };
  struct Case {
    std::string file;
    AttributeBandValues band;
    std::vector<std::string> fragments;
  };
  for (const Case& c : {Case{"unnamed.tif", {"blocksize", everywhere(2.0)}, {"band 2", "'blocksize'"}},
                        Case{"shape.tif", {"shape", everywhere(7.0)}, {"cell (column 6, row 6)", "shape 7"}},
                        Case{"size.tif", {"block_size", everywhere(-1.0)}, {"cell (column 6, row 6)", "block_size -1"}},
                        Case{"mass.tif", {"mass", everywhere(1e9)}, {"cell (column 6, row 6)", "mass"}}}) {
    write_release_raster(folder_ / c.file, cells, {c.band});
    try {
      read_release(folder_ / c.file, dem_, CrsOption{}, run_rock_);
      ADD_FAILURE() << c.file << ": no error";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(c.file), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      for (const std::string& fragment : c.fragments) EXPECT_NE(message.find(fragment), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace talus::gis
