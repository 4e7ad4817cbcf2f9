// `talus rockfall --mode full` with pre-fractured blocks (issue 4, Deliver 6: paper 3.1, fig. 4)
// end to end on the sample scene: 20 of its release cells (every 13th of
// sample_dem/rockfall_release.gpkg), one 1 m sphere each cut into two halves ([rock]
// fracture_parts = 2, the default strength of 1000 kN). The run succeeds, its layers pass
// tests/support/layer_contract.hpp, run.json records the parameters and the fragments (the bonds
// form a tree, so each broken bond adds one fragment), every fragment stops once, and the layers
// are the same at 1 and 2 threads. Fast mode and part counts other than 1, 2, 4, 8 are refused.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>

#include <gdal_priv.h>
#include <nlohmann/json.hpp>
#include <ogrsf_frmts.h>

#include "layer_contract.hpp"
#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

const char* const kLayers[] = {"reach_probability", "passages", "deposits", "energy_max", "energy_p95",
                               "jump_height_p95", "velocity_max", "energy_loss_friction", "energy_loss_deformation"};

// Every 13th release point of the sample scene (20 of 260), written to `path` in its CRS.
void write_release_subset(const fs::path& path) {
  GDALAllRegister();
  const auto sample = test::source_dir() / "sample_dem" / "rockfall_release.gpkg";
  GDALDatasetUniquePtr dataset(GDALDataset::Open(sample.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  ASSERT_TRUE(dataset) << sample;
  OGRLayer* layer = dataset->GetLayer(0);
  std::vector<test::VectorFeature> subset;
  int index = 0;
  for (const auto& feature : *layer) {
    if (index++ % 13 != 0) continue;
    char* wkt = nullptr;
    feature->GetGeometryRef()->exportToWkt(&wkt);
    subset.push_back({wkt, 0.0});
    CPLFree(wkt);
  }
  ASSERT_EQ(subset.size(), 20u);
  test::write_vector(path, "EPSG:31287", subset, false);
}

std::vector<std::string> fracture_arguments(const fs::path& root, const fs::path& out, const std::string& mode,
                                            const std::string& threads) {
  const auto sample = test::source_dir() / "sample_dem";
  return {"rockfall", "--mode", mode, "--dem", (sample / "dem.tif").string(), "--lithology",
          (sample / "lithology.tif").string(), "--vegetation", (sample / "vegetation.tif").string(), "--release",
          (root / "release.gpkg").string(), "--scenario", (root / "halves.toml").string(), "--out", out.string(),
          "--runs", "1", "--threads", threads};
}

class SampleFracture : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = test::fresh_folder("rockfall_fracture_sample");
    write_release_subset(root_ / "release.gpkg");
    std::ofstream(root_ / "halves.toml") << "[rock]\nfracture_parts = 2\n";
    for (const auto& [name, threads] : {std::pair{"t1", "1"}, {"t2", "2"}}) {
      results_[name] = test::run_talus(fracture_arguments(root_, root_ / name, "full", threads), root_);
    }
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  static fs::path root_;
  static std::map<std::string, test::ProgramResult> results_;
};
fs::path SampleFracture::root_;
std::map<std::string, test::ProgramResult> SampleFracture::results_;

TEST_F(SampleFracture, WritesEveryLayerOfTheContract) {
  for (const auto& [name, result] : results_) ASSERT_EQ(result.exit_code, 0) << name << ": " << result.err;
  EXPECT_EQ(test::layer_contract_problems("rockfall", root_ / "t2", test::source_dir() / "sample_dem/dem.tif"),
            test::kNoProblems);
}

TEST_F(SampleFracture, RecordsTheFragmentsAndEveryStop) {
  ASSERT_EQ(results_["t2"].exit_code, 0) << results_["t2"].err;
  std::ifstream file(root_ / "t2" / "run.json");
  const nlohmann::json record = nlohmann::json::parse(file);
  EXPECT_EQ(record["parameters"]["rock"]["fracture_parts"], 2);
  EXPECT_EQ(record["parameters"]["rock"]["fracture_strength"], 1000.0);  // kN, the default
  const nlohmann::json& counts = record["counts"];
  EXPECT_EQ(counts["trajectories"], 20);
  // 1000 kN breaks most 1 m spheres at their first impact (19 of 20 at this seed).
  const auto fragments = counts["fragments"].get<std::uint64_t>();
  EXPECT_GE(fragments, 10u);
  EXPECT_LE(fragments, 20u);  // two halves: at most one break per trajectory
  std::uint64_t stops = 0;
  for (const auto& [reason, count] : counts["stop_reasons"].items()) stops += count.get<std::uint64_t>();
  EXPECT_EQ(stops, 20u + fragments);
  // Every deposit is a fragment's rest: the deposits layer counts the halves, not the trajectories.
  double deposits = 0;
  for (const float value : test::read_band(root_ / "t2" / "deposits.tif")) deposits += value > 0 ? value : 0;
  EXPECT_EQ(deposits, counts["stop_reasons"]["at_rest"].get<double>());
}

TEST_F(SampleFracture, SameLayersAtOneAndTwoThreads) {
  for (const char* layer : kLayers) {
    const auto one = test::read_band(root_ / "t1" / (std::string(layer) + ".tif"));
    const auto two = test::read_band(root_ / "t2" / (std::string(layer) + ".tif"));
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(float)), 0) << layer << " differs";
  }
}

// Input errors (exit code 2), before any output: fast mode moves intact rocks only, and a block
// is cut into 1, 2, 4 or 8 parts.
TEST_F(SampleFracture, RefusesFastModeAndOtherPartCounts) {
  const test::ProgramResult fast = test::run_talus(fracture_arguments(root_, root_ / "fast", "fast", "1"), root_);
  EXPECT_EQ(fast.exit_code, 2) << fast.err;
  EXPECT_NE(fast.err.find("fracture_parts"), std::string::npos) << fast.err;
  EXPECT_FALSE(fs::exists(root_ / "fast" / "run.json"));
  std::ofstream(root_ / "three.toml") << "[rock]\nfracture_parts = 3\n";
  std::vector<std::string> arguments = fracture_arguments(root_, root_ / "three", "full", "1");
  for (std::size_t k = 0; k + 1 < arguments.size(); ++k) {
    if (arguments[k] == "--scenario") arguments[k + 1] = (root_ / "three.toml").string();
  }
  const test::ProgramResult three = test::run_talus(arguments, root_);
  EXPECT_EQ(three.exit_code, 2) << three.err;
  EXPECT_NE(three.err.find("fracture_parts 3"), std::string::npos) << three.err;
}

}  // namespace
}  // namespace talus
