// The layer-contract check itself (tests/support/layer_contract.hpp): it passes a real run's
// folder and names each way in which a damaged copy of that folder breaks the contract, so the
// tests that rely on it can fail.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "layer_contract.hpp"
#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

bool names(const std::vector<std::string>& problems, const std::string& line) {
  return std::ranges::find(problems, line) != problems.end();
}

TEST(LayerContract, PassesARunAndNamesEachBreach) {
  const auto root = test::fresh_folder("layer_contract");
  const auto sample = test::source_dir() / "sample_dem";
  const auto dem = sample / "dem.tif";
  const auto run = test::run_talus({"rockfall", "--dem", dem.string(), "--release",
                                    (sample / "rockfall_release.gpkg").string(), "--out", "run", "--runs", "1"},
                                   root);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(test::layer_contract_problems("rockfall", root / "run", dem), test::kNoProblems);

  fs::copy(root / "run", root / "broken");
  fs::remove(root / "broken/energy_max.qml");
  fs::remove(root / "broken/deposits.tif");
  GDALAllRegister();
  {  // passages as a plain Float64 GeoTIFF
    GDALDatasetUniquePtr source(GDALDataset::Open((root / "run/passages.tif").c_str(), GDAL_OF_RASTER));
    ASSERT_TRUE(source);
    GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
    const auto copy = root / "broken/passages_float64.tif";
    GDALDataset* wide = gtiff->Create(copy.c_str(), source->GetRasterXSize(), source->GetRasterYSize(), 1,
                                      GDT_Float64, nullptr);
    double geotransform[6];
    source->GetGeoTransform(geotransform);
    wide->SetGeoTransform(geotransform);
    wide->SetSpatialRef(source->GetSpatialRef());
    wide->GetRasterBand(1)->SetNoDataValue(-9999.0);
    wide->GetRasterBand(1)->SetDescription("Passages");
    GDALClose(wide);
    fs::rename(copy, root / "broken/passages.tif");
  }
  const auto problems = test::layer_contract_problems("rockfall", root / "broken", dem);
  EXPECT_TRUE(names(problems, "energy_max.qml: missing beside energy_max.tif"));
  EXPECT_TRUE(names(problems, "deposits.tif: missing"));
  EXPECT_TRUE(names(problems, "passages.tif: type Float64, not Float32"));
  EXPECT_TRUE(names(problems, "passages.tif: not a Cloud Optimized GeoTIFF"));
  EXPECT_EQ(problems.size(), 4u) << ::testing::PrintToString(problems);

  // The same folder against another DEM: every layer's grid differs.
  const auto other = test::layer_contract_problems("rockfall", root / "run", test::data_dir() / "fluchthorn_bad_crs/fluchthorn.tif");
  EXPECT_TRUE(names(other, "reach_probability.tif: its geotransform is not the DEM's"));
  EXPECT_TRUE(names(other, "reach_probability.tif: its CRS is not the DEM's"));
}

}  // namespace
}  // namespace talus
