// LayerWriter: the output-layer contract of docs/architecture.md section 3, read back with GDAL and QGIS.
#include "talus/gis/layer_writer.hpp"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "talus/core/errors.hpp"
#include "talus/gis/folder_manifest.hpp"
#include "talus/gis/gdal_dataset.hpp"
#include "test_paths.hpp"

namespace talus::gis {
namespace {

namespace fs = std::filesystem;

constexpr float kLayerNodata = -9999.0f;

// Every layer of the contract with its description and unit.
const std::vector<LayerDescription> kContractLayers = {
    {"reach_probability", "Reach probability", ""},
    {"passages", "Passages", ""},
    {"source_count", "Release sources reaching the cell", ""},
    {"deposits", "Deposited rocks", ""},
    {"energy_max", "Maximum kinetic energy", "kJ"},
    {"energy_p95", "95th percentile of kinetic energy", "kJ"},
    {"jump_height_p95", "95th percentile of jump height", "m"},
    {"velocity_max", "Maximum velocity", "m/s"},
    {"energy_loss_friction", "Energy lost to friction", "kJ"},
    {"energy_loss_deformation", "Energy lost to ground deformation", "kJ"},
    {"flow_depth_max", "Maximum flow depth", "m"},
    {"pressure_max", "Maximum pressure", "kPa"},
    {"deposit_depth", "Deposit depth", "m"},
    {"arrival_time", "Arrival time", "s"},
    {"erosion_depth", "Erosion depth", "m"},
};

std::string epsg_wkt(int code) {
  OGRSpatialReference srs;
  srs.importFromEPSG(code);
  return wkt_of(&srs);
}

// A projected grid whose spec uses another nodata (-32768) than the layers: a rectangular
// hole and a NaN cell are invalid, the left columns are 0 ("never reached").
Grid<float> sample_grid(int width, int height, std::string crs_wkt) {
  GridSpec spec;
  spec.width = width;
  spec.height = height;
  spec.geotransform = {612000.0, 5.0, 0.0, 385000.0, 0.0, -5.0};
  spec.crs_wkt = std::move(crs_wkt);
  spec.nodata = -32768.0;
  Grid<float> grid(spec);
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c) grid.at(c, r) = c < 10 ? 0.0f : 0.25f * static_cast<float>(c + r);
  for (int r = height / 4; r < height / 2; ++r)
    for (int c = width / 4; c < width / 2; ++c) grid.at(c, r) = -32768.0f;
  grid.at(5, 5) = std::numeric_limits<float>::quiet_NaN();
  return grid;
}

std::set<std::string> names_in(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.insert(entry.path().filename().string());
  return names;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

GDALDatasetUniquePtr open_layer(const fs::path& path) {
  ensure_gdal_ready();
  return GDALDatasetUniquePtr(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
}

const fs::path kPython = "/usr/bin/python3";

// Runs /usr/bin/python3 with the arguments (already quoted); its exit status.
int run_python(const std::string& arguments) {
  const int status = std::system((kPython.string() + " " + arguments).c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string quoted(const std::string& text) { return "'" + text + "'"; }

TEST(LayerWriter, WritesAFloat32CloudOptimizedGeoTiffOnTheGridWithItsProperties) {
  const auto folder = test::fresh_folder("layer_writer_cog");
  const auto grid = sample_grid(300, 200, epsg_wkt(31287));
  {
    LayerWriter writer(folder, {{"TALUS_PROCESS", "rock fall"}, {"TALUS_SCENARIO", "runs = 10"}});
    writer.add(grid, {"energy_max", "Maximum kinetic energy", "kJ"});
    writer.commit();
  }
  EXPECT_EQ(names_in(folder), (std::set<std::string>{"energy_max.tif", "energy_max.qml", "energy_max.qmd", kFolderManifestName}));
  // The QGIS metadata: a title naming the process, an abstract with the unit and scenario.
  const std::string qmd = read_text(folder / "energy_max.qmd");
  EXPECT_NE(qmd.find("<title>Maximum kinetic energy (rock fall)</title>"), std::string::npos) << qmd;
  EXPECT_NE(qmd.find("<abstract>Maximum kinetic energy (kJ), rock fall hazard layer written by Talus"), std::string::npos)
      << qmd;
  EXPECT_NE(qmd.find("Scenario: runs = 10."), std::string::npos) << qmd;
  EXPECT_EQ(read_text(folder / "energy_max.qml"), *embedded_style("energy_max"));

  const auto dataset = open_layer(folder / "energy_max.tif");
  ASSERT_TRUE(dataset);
  ASSERT_EQ(dataset->GetRasterCount(), 1);
  EXPECT_EQ(dataset->GetRasterXSize(), 300);
  EXPECT_EQ(dataset->GetRasterYSize(), 200);
  std::array<double, 6> geotransform{};
  ASSERT_EQ(dataset->GetGeoTransform(geotransform.data()), CE_None);
  EXPECT_EQ(geotransform, grid.spec().geotransform);
  ASSERT_NE(dataset->GetSpatialRef(), nullptr);
  OGRSpatialReference expected;
  expected.importFromEPSG(31287);
  expected.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // GDAL's order for datasets
  EXPECT_TRUE(dataset->GetSpatialRef()->IsSame(&expected));
  EXPECT_STREQ(dataset->GetSpatialRef()->GetAuthorityCode(nullptr), "31287");

  EXPECT_STREQ(dataset->GetMetadataItem("LAYOUT", "IMAGE_STRUCTURE"), "COG");
  EXPECT_STREQ(dataset->GetMetadataItem("COMPRESSION", "IMAGE_STRUCTURE"), "DEFLATE");
  EXPECT_STREQ(dataset->GetMetadataItem("PREDICTOR", "IMAGE_STRUCTURE"), "3");
  EXPECT_STREQ(dataset->GetMetadataItem("TALUS_VERSION"), TALUS_VERSION);
  EXPECT_STREQ(dataset->GetMetadataItem("TALUS_SCENARIO"), "runs = 10");

  GDALRasterBand* band = dataset->GetRasterBand(1);
  EXPECT_EQ(band->GetRasterDataType(), GDT_Float32);
  int has_nodata = 0;
  EXPECT_EQ(band->GetNoDataValue(&has_nodata), kLayerNodata);
  EXPECT_TRUE(has_nodata);
  EXPECT_STREQ(band->GetDescription(), "Maximum kinetic energy (kJ)");  // QGIS's legend heading
  EXPECT_STREQ(band->GetUnitType(), "kJ");
  EXPECT_GE(band->GetOverviewCount(), 1);

  std::vector<float> values(grid.size());
  ASSERT_EQ(band->RasterIO(GF_Read, 0, 0, 300, 200, values.data(), 300, 200, GDT_Float32, 0, 0, nullptr), CE_None);
  float min = std::numeric_limits<float>::max(), max = std::numeric_limits<float>::lowest();
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (grid.is_valid(i)) {
      ASSERT_EQ(values[i], grid[i]) << "cell " << i;
      min = std::min(min, grid[i]);
      max = std::max(max, grid[i]);
    } else {
      ASSERT_EQ(values[i], kLayerNodata) << "cell " << i;
    }
  }
  // Stored statistics, read without computing them (bForce false).
  double stored_min = 0, stored_max = 0, mean = 0, stddev = 0;
  ASSERT_EQ(band->GetStatistics(FALSE, FALSE, &stored_min, &stored_max, &mean, &stddev), CE_None);
  EXPECT_EQ(stored_min, min);
  EXPECT_EQ(stored_max, max);
  EXPECT_NE(band->GetMetadataItem("STATISTICS_MEAN"), nullptr);
}

// The overview cell of `factor` at (column, row) as the full-resolution cells it covers reduce:
// the largest valid value, or the earliest positive one (0 where none is positive).
float expected_overview_cell(const Grid<float>& grid, int factor, int column, int row, OverviewReduction reduction) {
  bool any = false;
  float result = 0.0f;
  for (int r = row * factor; r < std::min(grid.spec().height, (row + 1) * factor); ++r) {
    for (int c = column * factor; c < std::min(grid.spec().width, (column + 1) * factor); ++c) {
      if (!grid.is_valid(grid.index(c, r))) continue;
      const float value = grid.at(c, r);
      if (reduction == OverviewReduction::largest) {
        result = any ? std::max(result, value) : value;
      } else if (value > 0.0f && (!any || result <= 0.0f || value < result)) {
        result = value;
      }
      any = true;
    }
  }
  return any ? result : kLayerNodata;
}

// Issue 17, item 4: a zoomed-out or printed view reads the overviews, and an averaged overview
// lowers a cell's maximum (a printed map dropped a hazard class). Every overview cell of a
// maximum layer is the largest of the cells it covers; of an arrival time, the earliest arrival.
TEST(LayerWriter, OverviewsKeepTheMaximumOrTheEarliestArrivalOfTheCellsTheyCover) {
  const auto folder = test::fresh_folder("layer_writer_overviews");
  Grid<float> grid = sample_grid(700, 300, epsg_wkt(31287));
  // Isolated peaks and arrivals among zeros: an average would dilute each to a quarter or less.
  for (int r = 0; r < 300; ++r)
    for (int c = 0; c < 700; ++c)
      if (grid.is_valid(grid.index(c, r))) grid.at(c, r) = (c % 7 == 3 && r % 5 == 1) ? 1000.0f + static_cast<float>(c) : 0.0f;
  {
    LayerWriter writer(folder, {});
    writer.add(grid, {"energy_max", "Maximum kinetic energy", "kJ"});
    writer.add(grid, {"arrival_time", "Arrival time", "s", OverviewReduction::earliest_positive});
    writer.commit();
  }
  for (const auto& [name, reduction] : {std::pair{"energy_max", OverviewReduction::largest},
                                        std::pair{"arrival_time", OverviewReduction::earliest_positive}}) {
    const auto dataset = open_layer(folder / (std::string(name) + ".tif"));
    ASSERT_TRUE(dataset);
    GDALRasterBand* band = dataset->GetRasterBand(1);
    ASSERT_EQ(band->GetOverviewCount(), 2) << name;  // 350 x 150 and 175 x 75: the second fits one tile
    for (int k = 0; k < band->GetOverviewCount(); ++k) {
      GDALRasterBand* overview = band->GetOverview(k);
      const int factor = 2 << k;
      const int width = overview->GetXSize(), height = overview->GetYSize();
      ASSERT_EQ(width, (700 + factor - 1) / factor);
      ASSERT_EQ(height, (300 + factor - 1) / factor);
      std::vector<float> values(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
      ASSERT_EQ(overview->RasterIO(GF_Read, 0, 0, width, height, values.data(), width, height, GDT_Float32, 0, 0,
                                   nullptr),
                CE_None);
      int peaks = 0;
      for (int row = 0; row < height; ++row) {
        for (int column = 0; column < width; ++column) {
          const float expected = expected_overview_cell(grid, factor, column, row, reduction);
          ASSERT_EQ(values[static_cast<std::size_t>(row) * width + column], expected)
              << name << " overview " << k << " cell " << column << ", " << row;
          if (expected >= 1000.0f) ++peaks;
        }
      }
      EXPECT_GT(peaks, 1000) << name;  // the cells checked hold thousands of isolated peaks
    }
  }
}

TEST(LayerOverviews, FactorsHalveUntilTheCoarsestFitsOneTile) {
  EXPECT_EQ(overview_factors(700, 300, 256), (std::vector<int>{2, 4}));
  EXPECT_EQ(overview_factors(417, 915, 256), (std::vector<int>{2, 4}));
  EXPECT_EQ(overview_factors(512, 100, 256), (std::vector<int>{2}));
  EXPECT_TRUE(overview_factors(256, 256, 256).empty());
  EXPECT_TRUE(overview_factors(1, 1, 256).empty());
}

TEST(LayerWriter, WritesALayerWithoutCrsOrValidCellsWithoutStatistics) {
  const auto folder = test::fresh_folder("layer_writer_empty");
  auto grid = sample_grid(40, 30, "");
  for (auto& value : grid.values()) value = static_cast<float>(grid.spec().nodata);
  LayerWriter writer(folder, {});
  writer.add(grid, {"passages", "Passages", ""});
  writer.commit();

  const auto dataset = open_layer(folder / "passages.tif");
  ASSERT_TRUE(dataset);
  EXPECT_EQ(dataset->GetSpatialRef(), nullptr);
  EXPECT_STREQ(dataset->GetRasterBand(1)->GetUnitType(), "");
  EXPECT_EQ(dataset->GetRasterBand(1)->GetMetadataItem("STATISTICS_MINIMUM"), nullptr);
  float corner = 0;
  ASSERT_EQ(dataset->GetRasterBand(1)->RasterIO(GF_Read, 39, 29, 1, 1, &corner, 1, 1, GDT_Float32, 0, 0, nullptr),
            CE_None);
  EXPECT_EQ(corner, kLayerNodata);
}

TEST(LayerWriter, ShowsNothingBeforeCommitAndLeavesNothingWhenNeverCommitted) {
  const auto folder = test::fresh_folder("layer_writer_uncommitted");
  const auto grid = sample_grid(50, 40, epsg_wkt(31287));
  EXPECT_THROW(
      {
        LayerWriter writer(folder, {});
        writer.add(grid, {"deposits", "Deposited rocks", ""});
        std::ofstream(writer.temporary_path("run.json")) << "{}";
        EXPECT_TRUE(fs::is_empty(folder)) << "files visible before commit";
        throw std::runtime_error("the run failed");
      },
      std::runtime_error);
  EXPECT_TRUE(fs::is_empty(folder));
  EXPECT_EQ(names_in(folder.parent_path()).count(folder.filename().string()), 1u);
  for (const auto& name : names_in(folder.parent_path()))
    EXPECT_EQ(name.find("." + folder.filename().string() + ".talus-"), std::string::npos) << name << " left behind";
}

TEST(LayerWriter, CommitsTheFilesOfTheSetAndDropsALayerThatFailed) {
  const auto folder = test::fresh_folder("layer_writer_failed_layer");
  LayerWriter writer(folder, {});
  writer.add(sample_grid(50, 40, epsg_wkt(31287)), {"velocity_max", "Maximum velocity", "m/s"});
  try {
    writer.add(sample_grid(50, 40, "not a CRS"), {"pressure_max", "Maximum pressure", "kPa"});
    ADD_FAILURE() << "no error for a layer with a bad CRS";
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find((folder / "pressure_max.tif").string()), std::string::npos) << message;
  }
  // A folder in the way of the style: the layer fails after its GeoTIFF was written.
  const auto blocker = writer.staging_folder() / "flow_depth_max.qml";
  fs::create_directory(blocker);
  std::ofstream(blocker / "blocker") << "x";
  EXPECT_THROW(writer.add(sample_grid(50, 40, epsg_wkt(31287)), {"flow_depth_max", "Maximum flow depth", "m"}),
               std::runtime_error);
  EXPECT_FALSE(fs::exists(writer.staging_folder() / "flow_depth_max.tif"));
  fs::remove_all(blocker);
  std::ofstream(writer.temporary_path("run.json")) << "{}";
  writer.commit();
  EXPECT_EQ(names_in(folder),
            (std::set<std::string>{"velocity_max.tif", "velocity_max.qml", "velocity_max.qmd", "run.json", kFolderManifestName}));
  EXPECT_EQ(read_text(folder / "run.json"), "{}");
}

TEST(LayerWriter, RefusesALayerWithoutStyle) {
  const auto folder = test::fresh_folder("layer_writer_no_style");
  LayerWriter writer(folder, {});
  EXPECT_THROW(writer.add(sample_grid(20, 10, ""), {"no_such_layer", "Nothing", ""}), std::logic_error);
  EXPECT_TRUE(fs::is_empty(folder));
}

TEST(LayerWriter, OutputFolderThatCannotBeCreatedIsAnInputErrorNamingIt) {
  const auto folder = test::fresh_folder("layer_writer_bad_folder");
  std::ofstream(folder / "plain_file") << "not a folder";
  const auto out = folder / "plain_file" / "out";
  try {
    LayerWriter writer(out, {});
    FAIL() << "no error for " << out;
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(out.string()), std::string::npos) << error.what();
  }
}

TEST(LayerWriter, OpensStyledInQgis) {
  if (!fs::exists(kPython)) GTEST_SKIP() << kPython << " (with python3-qgis) is not installed";
  const auto folder = test::fresh_folder("layer_writer_qgis");
  {
    LayerWriter writer(folder, {});
    writer.add(sample_grid(300, 200, epsg_wkt(31287)), {"energy_max", "Maximum kinetic energy", "kJ"});
    writer.commit();
  }
  const auto script = test::source_dir() / "tests/gis/qgis/check_layer_in_qgis.py";
  EXPECT_EQ(run_python(quoted(script.string()) + " EPSG:31287 " + quoted((folder / "energy_max.tif").string()) +
                       " 'Maximum kinetic energy (kJ)'"),
            0);
}

TEST(LayerWriter, EveryContractLayerHasTheStyleOfGisStylesAndQgisAppliesIt) {
  if (!fs::exists(kPython)) GTEST_SKIP() << kPython << " (with python3-qgis) is not installed";
  const auto folder = test::fresh_folder("layer_writer_all_styles");
  const auto wkt = epsg_wkt(31287);
  std::string layers;
  {
    LayerWriter writer(folder, {});
    for (const auto& layer : kContractLayers) {
      const auto style = embedded_style(layer.name);
      ASSERT_TRUE(style) << layer.name;
      EXPECT_EQ(*style, read_text(test::source_dir() / "gis/styles" / (layer.name + ".qml"))) << layer.name;
      writer.add(sample_grid(30, 20, wkt), layer);
      const std::string band = layer.unit.empty() ? layer.description : layer.description + " (" + layer.unit + ")";
      layers += " " + quoted((folder / (layer.name + ".tif")).string()) + " " + quoted(band);
    }
    writer.commit();
  }
  const auto script = test::source_dir() / "tests/gis/qgis/check_layer_in_qgis.py";
  EXPECT_EQ(run_python(quoted(script.string()) + " " + quoted(wkt) + layers), 0);
}

TEST(LayerWriter, StylesAreWhatMakeStylesWrites) {
  if (!fs::exists(kPython)) GTEST_SKIP() << kPython << " is not installed";
  const auto folder = test::fresh_folder("layer_writer_make_styles");
  const auto styles = test::source_dir() / "gis/styles";
  ASSERT_EQ(run_python(quoted((styles / "make_styles.py").string()) + " " + quoted(folder.string())), 0);
  std::set<std::string> committed;
  for (const auto& entry : fs::directory_iterator(styles))
    if (entry.path().extension() == ".qml") committed.insert(entry.path().filename().string());
  EXPECT_EQ(names_in(folder), committed);
  for (const auto& name : committed) EXPECT_EQ(read_text(folder / name), read_text(styles / name)) << name;
}

}  // namespace
}  // namespace talus::gis
