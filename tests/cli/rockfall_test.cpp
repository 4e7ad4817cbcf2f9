// `talus rockfall --mode fast` end to end on the sample scene (issue 3, "Done when"): every
// layer passes tests/support/layer_contract.hpp and opens styled in QGIS; same seed gives
// identical layers at 1 and 2 threads; another seed gives different layers with consistent
// statistics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <tuple>

#include "layer_contract.hpp"
#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "talus/gis/folder_manifest.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

const char* const kLayers[] = {"reach_probability", "passages", "source_count", "deposits", "energy_max", "energy_p95",
                               "jump_height_p95", "velocity_max", "energy_loss_friction", "energy_loss_deformation"};

// 5 runs per source: the chunks of 8 runs that threads take then cut sources, so that two
// threads record runs of one source and source_count must unite them.
std::vector<std::string> sample_arguments(const fs::path& out, const std::string& seed, const std::string& threads) {
  const auto sample = test::source_dir() / "sample_dem";
  return {"rockfall", "--dem", (sample / "dem.tif").string(), "--lithology", (sample / "lithology.tif").string(),
          "--vegetation", (sample / "vegetation.tif").string(), "--release", (sample / "rockfall_release.gpkg").string(),
          "--out", out.string(), "--runs", "5", "--seed", seed, "--threads", threads};
}

int run_python(const std::string& arguments) { return std::system(("/usr/bin/python3 " + arguments).c_str()); }

class SampleRockfall : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = test::fresh_folder("rockfall_sample");
    for (const auto& [name, seed, threads] : {std::tuple{"seed1_t1", "1", "1"}, {"seed1_t2", "1", "2"}, {"seed2_t2", "2", "2"}}) {
      results_[name] = test::run_talus(sample_arguments(root_ / name, seed, threads), root_);
    }
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  static fs::path root_;
  static std::map<std::string, test::ProgramResult> results_;
};
fs::path SampleRockfall::root_;
std::map<std::string, test::ProgramResult> SampleRockfall::results_;

TEST_F(SampleRockfall, WritesEveryLayerOfTheContract) {
  for (const auto& [name, result] : results_) ASSERT_EQ(result.exit_code, 0) << name << ": " << result.err;
  EXPECT_EQ(test::layer_contract_problems("rockfall", root_ / "seed1_t2", test::source_dir() / "sample_dem/dem.tif"),
            test::kNoProblems);
  EXPECT_NE(results_["seed1_t2"].out.find("Layers written to"), std::string::npos);
  EXPECT_NE(results_["seed1_t2"].err.find("Progress: 100%"), std::string::npos);
  for (const auto& entry : fs::directory_iterator(root_ / "seed1_t2")) {
    if (entry.path().filename() == gis::kFolderManifestName) continue;
    EXPECT_NE(entry.path().filename().string().front(), '.') << "temporary file left: " << entry.path();
  }
}

TEST_F(SampleRockfall, LayersOpenStyledInQgis) {
  std::string arguments = (test::source_dir() / "tests/gis/qgis/check_layer_in_qgis.py").string() + " EPSG:31287";
  const std::map<std::string, std::string> descriptions = {
      {"reach_probability", "Reach probability per contributing source"},
      {"source_count", "Number of release sources reaching the cell"},
      {"energy_max", "Maximum kinetic energy (kJ)"},
      {"velocity_max", "Maximum velocity (m/s)"},
      {"intensity", "Intensity class by foen-2016"}};
  for (const auto& [layer, description] : descriptions) {
    arguments += " " + (root_ / "seed1_t2" / (layer + ".tif")).string() + " '" + description + "'";
  }
  EXPECT_EQ(run_python(arguments), 0);
}

TEST_F(SampleRockfall, SameSeedGivesIdenticalLayersAtOneAndTwoThreads) {
  for (const char* layer : kLayers) {
    const auto one = test::read_band(root_ / "seed1_t1" / (std::string(layer) + ".tif"));
    const auto two = test::read_band(root_ / "seed1_t2" / (std::string(layer) + ".tif"));
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(float)), 0) << layer << " differs";
  }
}

TEST_F(SampleRockfall, AnotherSeedGivesDifferentLayersWithConsistentStatistics) {
  const auto a = test::read_band(root_ / "seed1_t2" / "passages.tif");
  const auto b = test::read_band(root_ / "seed2_t2" / "passages.tif");
  ASSERT_EQ(a.size(), b.size());
  EXPECT_NE(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
  double reached_a = 0, reached_b = 0, deposits_a = 0, deposits_b = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    reached_a += a[i] > 0 ? 1 : 0;
    reached_b += b[i] > 0 ? 1 : 0;
  }
  const auto da = test::read_band(root_ / "seed1_t2" / "deposits.tif");
  const auto db = test::read_band(root_ / "seed2_t2" / "deposits.tif");
  for (std::size_t i = 0; i < da.size(); ++i) {
    deposits_a += da[i] > 0 ? da[i] : 0;
    deposits_b += db[i] > 0 ? db[i] : 0;
  }
  // 1300 trajectories each: the reached area and the number of deposits agree within 10 %.
  EXPECT_NEAR(reached_b / reached_a, 1.0, 0.10);
  EXPECT_NEAR(deposits_b / std::max(deposits_a, 1.0), 1.0, 0.10);
}

TEST(RockfallUsage, BadReleaseWritesNothing) {
  const auto work = test::fresh_folder("rockfall_bad_release");
  auto arguments = sample_arguments(work / "out", "1", "1");
  arguments[8] = (test::source_dir() / "sample_dem/lithology.tif").string();  // --release: a class raster of 1..6
  arguments[2] = (test::data_dir() / "fluchthorn_bad_crs/fluchthorn.tif").string();
  const auto result = test::run_talus(arguments, work);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_TRUE(fs::is_empty(work));
}

}  // namespace
}  // namespace talus
