// Reading and aligning the user's inputs: CRS rules, alignment, release layers, classes.
#include <gtest/gtest.h>

#include <ogr_spatialref.h>

#include <cmath>
#include <map>
#include <sstream>

#include "raster_fixtures.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/raster_alignment.hpp"
#include "talus/gis/release_reader.hpp"
#include "talus/gis/scene.hpp"
#include "test_paths.hpp"

namespace talus::gis {
namespace {

using test::RasterFixture;

std::map<int, double> class_shares(const Grid<double>& values) {
  std::map<int, double> shares;
  double total = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!values.is_valid(i)) continue;
    shares[static_cast<int>(std::lround(values[i]))] += 1.0;
    total += 1.0;
  }
  for (auto& [code, share] : shares) share /= total;
  return shares;
}

// Classes laid out in geographic coordinates: rings around a point and a diagonal band.
int geographic_class(double lon, double lat) {
  const double ring = std::hypot((lon - 9.013) * 0.68, lat - 47.0) / 0.0025;  // ~280 m per ring
  if (lat - 46.994 > 1.2 * (lon - 9.0) + 0.006) return 6;
  return 1 + static_cast<int>(std::floor(ring)) % 4;
}

class GeographicLithology : public ::testing::TestWithParam<double> {};

// Issue 2 test: a lithology raster in EPSG:4326 aligned onto a UTM DEM keeps each class's
// share within 1% (absolute) of the shares on the DEM cells.
TEST_P(GeographicLithology, KeepsClassSharesWithinOnePercent) {
  const auto folder = test::fresh_folder("geographic_lithology_" + std::to_string(static_cast<int>(GetParam() * 1e6)));
  RasterFixture dem;  // UTM 32N, 10 m cells, 2 km x 1.5 km near 9 E 47 N
  dem.width = 200;
  dem.height = 150;
  dem.x0 = 500000.0;
  dem.y0 = 5206000.0;
  write_raster(folder / "dem.tif", dem);

  RasterFixture lithology;
  lithology.crs = "EPSG:4326";
  lithology.cell = GetParam();
  lithology.x0 = 8.995;
  lithology.y0 = 47.01;
  lithology.width = static_cast<int>(0.04 / lithology.cell);
  lithology.height = static_cast<int>(0.035 / lithology.cell);
  lithology.integer = true;
  lithology.nodata = -1;
  lithology.value = [&](int c, int r) {
    return geographic_class(lithology.x0 + (c + 0.5) * lithology.cell, lithology.y0 - (r + 0.5) * lithology.cell);
  };
  write_raster(folder / "lithology.tif", lithology);

  const DemInput input = read_dem(folder / "dem.tif", CrsOption{});
  const AlignedRaster aligned =
      align_raster(folder / "lithology.tif", "lithology", input.elevation.spec(), ValueKind::classes, CrsOption{});

  // Truth: the class function evaluated at every DEM cell centre.
  OGRSpatialReference utm, wgs84;
  utm.importFromEPSG(32632);
  wgs84.importFromEPSG(4326);
  utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_geographic(OGRCreateCoordinateTransformation(&utm, &wgs84));
  Grid<double> truth(input.elevation.spec());
  const GridSpec& spec = truth.spec();
  for (int r = 0; r < spec.height; ++r) {
    for (int c = 0; c < spec.width; ++c) {
      double x = spec.node_x(c), y = spec.node_y(r);
      ASSERT_TRUE(to_geographic->Transform(1, &x, &y));
      truth.at(c, r) = geographic_class(x, y);
    }
  }
  const auto expected = class_shares(truth);
  const auto got = class_shares(aligned.values);
  ASSERT_EQ(expected.size(), 5u);
  for (const auto& [code, share] : expected) {
    ASSERT_TRUE(got.contains(code)) << "class " << code << " lost";
    EXPECT_NEAR(got.at(code), share, 0.01) << "class " << code << " aligned by " << aligned.method;
  }
}

// A finer source (mode of several cells) and a source of similar size (nearest cell).
INSTANTIATE_TEST_SUITE_P(SourceResolutions, GeographicLithology, ::testing::Values(0.00003, 0.0001));

TEST(DemReader, PixelIsPointIsGeoreferencedToTheRightHalfPixel) {
  const DemInput dem = read_dem(test::data_dir() / "mal_pixel_is_point/avaMal.tif", CrsOption{});
  const GridSpec& spec = dem.elevation.spec();
  // The file's tie point (166775.664152029, 353586.3405) is the centre of the first cell.
  EXPECT_NEAR(spec.node_x(0), 166775.664152029, 1e-6);
  EXPECT_NEAR(spec.node_y(0), 353586.340500009, 1e-6);
  EXPECT_NEAR(spec.geotransform[0], 166773.164152029, 1e-6);
  EXPECT_NEAR(spec.geotransform[3], 353588.840500009, 1e-6);
  bool noted = false;
  for (const auto& note : dem.notes) noted = noted || note.find("PixelIsPoint") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(DemReader, RefusesAGeographicCrsOnMetreCoordinates) {
  const auto path = test::data_dir() / "fluchthorn_bad_crs/fluchthorn.tif";
  try {
    read_dem(path, CrsOption{});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fluchthorn.tif"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("geographic"), std::string::npos);
  }
  const DemInput fixed = read_dem(path, parse_crs_option("EPSG:31254"));
  EXPECT_NE(fixed.crs_name.find("31254"), std::string::npos);
}

// A fuzz finding (docs/fuzzing.md): a raster in a geocentric CRS (ITRF92, EPSG:4914) made PROJ
// search for a transformation to the DEM's CRS for about a second per input; it is no map's
// CRS, and is refused at once, as the DEM and as any other raster.
TEST(DemReader, RefusesAGeocentricCrs) {
  const auto dir = test::fresh_folder("geocentric");
  RasterFixture geocentric;
  geocentric.crs = "EPSG:4914";
  geocentric.x0 = 11.0;
  geocentric.y0 = 47.0;
  geocentric.cell = 0.001;
  geocentric.width = geocentric.height = 4;
  test::write_raster(dir / "geocentric.tif", geocentric);
  const auto sample = test::source_dir() / "sample_dem";
  for (const bool as_dem : {true, false}) {
    SceneInputs inputs;
    inputs.dem = as_dem ? dir / "geocentric.tif" : sample / "dem.tif";
    if (!as_dem) inputs.lithology = dir / "geocentric.tif";
    try {
      load_scene(inputs);
      ADD_FAILURE() << "a geocentric CRS was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("geocentric.tif"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("is geocentric"), std::string::npos) << e.what();
    }
  }
}

TEST(DemReader, ReprojectsAGeographicDemToItsUtmZone) {
  const auto folder = test::fresh_folder("geographic_dem");
  RasterFixture dem;
  dem.crs = "EPSG:4326";
  dem.x0 = 11.0;
  dem.y0 = 47.3;
  dem.cell = 0.0001;
  write_raster(folder / "dem.tif", dem);
  const DemInput input = read_dem(folder / "dem.tif", CrsOption{});
  EXPECT_NE(input.crs_name.find("32632"), std::string::npos) << input.crs_name;
  bool noted = false;
  for (const auto& note : input.notes) noted = noted || note.find("reprojected") != std::string::npos;
  EXPECT_TRUE(noted);
  EXPECT_GT(input.elevation.spec().cell_width(), 5.0);
  EXPECT_LT(input.elevation.spec().cell_width(), 12.0);
}

// Issue 18, item 5: the raster fuzzer's finding, a DEM of 4 x 53,764 cells in degrees (53 degrees
// of latitude, one byte changed from a seed), that GDAL's warp would have made 640 x 53,760 cells
// in UTM (25 s and 3.7 GB): refused before any warping, with the growth named.
TEST(DemReader, RefusesAGeographicDemThatReprojectionWouldMultiply) {
  const auto path = test::source_dir() / "tests/fuzz/corpus/raster/finding-dem-degrees-53-degrees-tall.tif";
  try {
    read_dem(path, CrsOption{});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path.string(), 0), 0u) << message;
    EXPECT_NE(message.find(": in degrees, reprojected to EPSG:32632 it would need 640 x 53760 cells"), std::string::npos)
        << message;
    EXPECT_NE(message.find("160 times its own 4 x 53764"), std::string::npos) << message;
    EXPECT_NE(message.find("gdalwarp -t_srs"), std::string::npos) << message;
  }
}

TEST(DemReader, RefusesElevationsInFeet) {
  const auto folder = test::fresh_folder("feet_dem");
  RasterFixture dem;
  dem.unit = "ft";
  write_raster(folder / "dem.tif", dem);
  EXPECT_THROW(read_dem(folder / "dem.tif", CrsOption{}), InputError);
}

TEST(DemReader, TakesAZeroBorderAsNodata) {
  const DemInput dem = read_dem(test::data_dir() / "norway_forest/dem_5m_sn1.asc", parse_crs_option("EPSG:25833"));
  EXPECT_FALSE(dem.elevation.is_valid(0, 0));
  EXPECT_TRUE(dem.elevation.is_valid(177, 177));
  EXPECT_GT(dem.elevation.at(177, 177), 10.0);
}

TEST(DemReader, AssignsLocalCoordinates) {
  const DemInput dem = read_dem(test::data_dir() / "sthelens2021/pre_runout_DEM.asc", parse_crs_option("local"));
  EXPECT_TRUE(dem.elevation.spec().crs_wkt.empty());
  EXPECT_THROW(read_dem(test::data_dir() / "sthelens2021/pre_runout_DEM.asc", CrsOption{}), InputError);
}

class ReleaseLayers : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = test::fresh_folder("release_layers");
    write_raster(folder_ / "dem.tif", RasterFixture{});  // 400 x 300 m from (500000, 5200000)
    dem_ = read_dem(folder_ / "dem.tif", CrsOption{}).elevation;
  }
  std::filesystem::path folder_;
  Grid<double> dem_;
};

TEST_F(ReleaseLayers, BurnsPolygonsWithTheirDepth) {
  test::write_vector(folder_ / "polygon.gpkg", "EPSG:32632",
                     {{"POLYGON((500100 5199900,500200 5199900,500200 5199800,500100 5199800,500100 5199900))", -2.5}}, true);
  const ReleaseSet release = read_release(folder_ / "polygon.gpkg", dem_, CrsOption{});
  EXPECT_EQ(release.cell_count(), 100u);
  EXPECT_NEAR(release.area(), 10000.0, 1e-6);
  EXPECT_NEAR(release.vertical_volume(), 25000.0, 1e-3);
  EXPECT_FALSE(release.depths_from_surface_lowering);  // an attribute's sign says nothing of how it was measured
}

TEST_F(ReleaseLayers, ReprojectsPointsToTheDemCrs) {
  OGRSpatialReference utm, wgs84;
  utm.importFromEPSG(32632);
  wgs84.importFromEPSG(4326);
  utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_geographic(OGRCreateCoordinateTransformation(&utm, &wgs84));
  double x = 500155.0, y = 5199855.0;
  to_geographic->Transform(1, &x, &y);
  std::ostringstream wkt;
  wkt.precision(15);
  wkt << "POINT(" << x << " " << y << ")";
  test::write_vector(folder_ / "points.gpkg", "EPSG:4326", {{wkt.str(), 0}}, false);
  const ReleaseSet release = read_release(folder_ / "points.gpkg", dem_, CrsOption{});
  ASSERT_EQ(release.points.size(), 1u);
  EXPECT_NEAR(release.points[0].x, 500155.0, 0.01);
  EXPECT_NEAR(release.points[0].y, 5199855.0, 0.01);
}

TEST_F(ReleaseLayers, RefusesOutsideEmptyAndLines) {
  test::write_vector(folder_ / "outside.gpkg", "EPSG:32632", {{"POINT(600000 5100000)", 0}}, false);
  test::write_vector(folder_ / "empty.gpkg", "EPSG:32632", {}, false);
  test::write_vector(folder_ / "line.gpkg", "EPSG:32632", {{"LINESTRING(500100 5199900,500200 5199800)", 0}}, false);
  RasterFixture zeros;
  zeros.value = [](int, int) { return 0.0; };
  write_raster(folder_ / "zeros.tif", zeros);
  for (const char* name : {"outside.gpkg", "empty.gpkg", "line.gpkg", "zeros.tif"}) {
    try {
      read_release(folder_ / name, dem_, CrsOption{});
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

TEST_F(ReleaseLayers, ReadsARasterOfNegativeDepths) {
  RasterFixture depth;
  depth.value = [](int c, int r) { return (c < 5 && r < 4) ? -1.5 : 0.0; };
  write_raster(folder_ / "depth.tif", depth);
  const ReleaseSet release = read_release(folder_ / "depth.tif", dem_, CrsOption{});
  EXPECT_EQ(release.cell_count(), 20u);
  EXPECT_NEAR(release.vertical_volume(), 20 * 100 * 1.5, 1e-6);
  // The surface lowering of a DEM of difference: `auto` reads it as vertical (docs/inputs.md).
  EXPECT_TRUE(release.depths_from_surface_lowering);
  depth.value = [](int c, int r) { return (c < 5 && r < 4) ? 1.5 : 0.0; };
  write_raster(folder_ / "positive.tif", depth);
  EXPECT_FALSE(read_release(folder_ / "positive.tif", dem_, CrsOption{}).depths_from_surface_lowering);
}

TEST(Scene, NamesUnknownLithologyCodes) {
  const auto folder = test::fresh_folder("unknown_lithology");
  write_raster(folder / "dem.tif", RasterFixture{});
  RasterFixture lithology;
  lithology.integer = true;
  lithology.value = [](int c, int) { return c < 10 ? 42.0 : 4.0; };
  write_raster(folder / "lithology.tif", lithology);
  SceneInputs inputs;
  inputs.dem = folder / "dem.tif";
  inputs.lithology = folder / "lithology.tif";
  try {
    load_scene(inputs);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("42"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("lithology.tif"), std::string::npos) << e.what();
  }
}

TEST(Scene, TellsVegetationClassesFromCoefficients) {
  const auto folder = test::fresh_folder("vegetation_kinds");
  write_raster(folder / "dem.tif", RasterFixture{});
  RasterFixture classes;
  classes.integer = true;
  classes.value = [](int c, int) { return c < 20 ? 0.0 : 4.0; };
  write_raster(folder / "classes.tif", classes);
  RasterFixture coefficients;
  coefficients.value = [](int c, int) { return 0.001 * c; };
  write_raster(folder / "coefficients.tif", coefficients);

  SceneInputs inputs;
  inputs.dem = folder / "dem.tif";
  inputs.vegetation = folder / "classes.tif";
  const Scene with_classes = load_scene(inputs);
  ASSERT_TRUE(with_classes.vegetation_classes.has_value());
  EXPECT_EQ(with_classes.vegetation_classes->at(30, 5), 4);
  EXPECT_EQ(with_classes.vegetation.at(30, 5), with_classes.materials.find_vegetation(4)->deperdition);

  inputs.vegetation = folder / "coefficients.tif";
  const Scene with_coefficients = load_scene(inputs);
  EXPECT_FALSE(with_coefficients.vegetation_classes.has_value());
  EXPECT_NEAR(with_coefficients.vegetation.at(30, 5), 0.030, 1e-9);
}

}  // namespace
}  // namespace talus::gis
