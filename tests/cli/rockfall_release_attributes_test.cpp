// `talus rockfall` with rock-fall attributes on the release features (issue 16): attributes
// that are NULL or equal to the run's own values give byte-identical layers to a layer without
// the fields; other values change the run and are counted in run.json; bad values stop the run
// with exit code 2 and one line naming the file, the feature and the field, before anything
// is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>

#include <nlohmann/json.hpp>

#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;
using test::LayerFeature;
using test::LayerField;

const std::vector<LayerField> kFields = {{"shape", true}, {"block_size", true}, {"density", false},
                                         {"mass", false},  {"vx", false},        {"vy", false},
                                         {"vz", false},    {"release_height", false}};
const char* const kPoints[] = {"POINT(500105 5199975)", "POINT(500205 5199975)", "POINT(500305 5199975)"};

// The three points, each with the same attribute values.
std::vector<LayerFeature> points_with(const std::vector<std::optional<std::string>>& values) {
  std::vector<LayerFeature> features;
  for (const char* wkt : kPoints) features.push_back({wkt, values});
  return features;
}

// A 400 x 300 m slope falling south at 5 m per 10 m cell.
void write_slope(const fs::path& path) {
  test::RasterFixture dem;
  dem.value = [](int, int row) { return 1000.0 - 5.0 * row; };
  write_raster(path, dem);
}

std::vector<std::string> rockfall_arguments(const fs::path& inputs, const fs::path& release, const fs::path& out) {
  return {"rockfall", "--dem", (inputs / "dem.tif").string(), "--release", release.string(), "--out", out.string(),
          "--runs", "4", "--seed", "1", "--threads", "2"};
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

class ReleaseAttributeRuns : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = test::fresh_folder("rockfall_release_attributes");
    write_slope(root_ / "dem.tif");
    std::vector<test::VectorFeature> plain;
    for (const char* wkt : kPoints) plain.push_back({wkt, 0});
    test::write_vector(root_ / "plain.gpkg", "EPSG:32632", plain, false);
    test::write_layer(root_ / "nulls.gpkg", "EPSG:32632", kFields, points_with(std::vector<std::optional<std::string>>(8)));
    test::write_layer(root_ / "run_values.gpkg", "EPSG:32632", kFields,
                      points_with({"sphere", "1", "2700", std::nullopt, "0", "0", "0", "0.5"}));
    test::write_layer(root_ / "thrown.gpkg", "EPSG:32632", kFields,
                      points_with({"box", "2,1.5,1", "3000", std::nullopt, "10", "0", "2", "1"}));
    for (const char* name : {"plain", "nulls", "run_values", "thrown"}) {
      results_[name] = test::run_talus(rockfall_arguments(root_, root_ / (std::string(name) + ".gpkg"), root_ / name), root_);
    }
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  static fs::path root_;
  static std::map<std::string, test::ProgramResult> results_;
};
fs::path ReleaseAttributeRuns::root_;
std::map<std::string, test::ProgramResult> ReleaseAttributeRuns::results_;

const char* const kLayers[] = {"reach_probability", "passages", "deposits", "energy_max", "energy_p95",
                               "jump_height_p95", "velocity_max", "energy_loss_friction", "energy_loss_deformation"};

TEST_F(ReleaseAttributeRuns, NullsAndTheRunsOwnValuesGiveIdenticalLayers) {
  for (const auto& [name, result] : results_) ASSERT_EQ(result.exit_code, 0) << name << ": " << result.err;
  for (const char* run : {"nulls", "run_values"}) {
    for (const char* layer : kLayers) {
      const std::string file = std::string(layer) + ".tif";
      const std::string plain = file_bytes(root_ / "plain" / file);
      ASSERT_FALSE(plain.empty()) << file;
      EXPECT_EQ(file_bytes(root_ / run / file), plain) << run << "/" << file << " differs from plain/" << file;
    }
  }
  EXPECT_EQ(read_json(root_ / "nulls/run.json")["counts"]["sources_with_attributes"], 0);
  EXPECT_EQ(read_json(root_ / "run_values/run.json")["counts"]["sources_with_attributes"], 3);
}

TEST_F(ReleaseAttributeRuns, ThrownBlocksChangeTheLayers) {
  ASSERT_EQ(results_["thrown"].exit_code, 0) << results_["thrown"].err;
  for (const char* layer : {"passages", "energy_max"}) {
    const std::string file = std::string(layer) + ".tif";
    EXPECT_NE(file_bytes(root_ / "thrown" / file), file_bytes(root_ / "plain" / file)) << file;
  }
  // Thrown 10 m/s eastwards, the blocks reach the cells two columns east of their points (10,
  // 20, 30), which rocks starting at rest on this south-falling slope never reach.
  const auto plain = test::read_band(root_ / "plain/passages.tif");
  const auto thrown = test::read_band(root_ / "thrown/passages.tif");
  const auto reached_east = [](const std::vector<float>& passages) {
    int count = 0;
    for (int row = 0; row < 30; ++row) {
      for (int col : {12, 22, 32}) count += passages[static_cast<std::size_t>(row * 40 + col)] > 0 ? 1 : 0;
    }
    return count;
  };
  EXPECT_EQ(reached_east(plain), 0);
  EXPECT_GT(reached_east(thrown), 0);
  EXPECT_EQ(read_json(root_ / "thrown/run.json")["counts"]["sources_with_attributes"], 3);
}

struct BadAttribute {
  std::string name;                                  // test name
  std::vector<LayerFeature> features;                // the bad one second, so that its index shows
  std::vector<std::string> phrases;                  // what the message must say
};

void PrintTo(const BadAttribute& bad, std::ostream* os) { *os << bad.name; }

const LayerFeature kGoodPoint = {"POINT(500105 5199975)", {"sphere", "1"}};

BadAttribute bad_point(const std::string& name, const std::vector<std::optional<std::string>>& values,
                       const std::vector<std::string>& phrases) {
  return {name, {kGoodPoint, {"POINT(500205 5199975)", values}}, phrases};
}

class BadReleaseAttributes : public ::testing::TestWithParam<BadAttribute> {};

TEST_P(BadReleaseAttributes, ExitTwoWithOneLineNamingFeatureAndFieldAndWriteNothing) {
  const BadAttribute& bad = GetParam();
  const auto inputs = test::fresh_folder("bad_attribute_inputs_" + bad.name);
  write_slope(inputs / "dem.tif");
  test::write_layer(inputs / "release.gpkg", "EPSG:32632", kFields, bad.features);
  const auto work = test::fresh_folder("bad_attribute_run_" + bad.name);
  const auto result = test::run_talus(rockfall_arguments(inputs, inputs / "release.gpkg", work / "out"), work);
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(result.err.rfind("talus: error: " + (inputs / "release.gpkg").string() + " (release): feature 2 (FID 2): ", 0),
            0u)
      << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  for (const auto& phrase : bad.phrases) EXPECT_NE(result.err.find(phrase), std::string::npos) << result.err;
  EXPECT_TRUE(fs::is_empty(work)) << "something was written";
  fs::remove_all(inputs);
}

const std::optional<std::string> kNull;

INSTANTIATE_TEST_SUITE_P(
    Rockfall, BadReleaseAttributes,
    ::testing::Values(
        bad_point("negative_size", {kNull, "-1"}, {"block_size -1: axes must lie between 0.01 and 100 m"}),
        bad_point("size_of_two_axes", {"box", "1,2"}, {"block_size 1,2: give D or A,B,C in metres"}),
        bad_point("sphere_of_three_axes", {kNull, "1,2,3"}, {"block_size 1,2,3: a sphere has one diameter"}),
        bad_point("density_and_mass", {kNull, kNull, "2700", "1400"},
                  {"density 2700 and mass 1400: give one of them, not both"}),
        bad_point("density_out_of_range", {kNull, kNull, "100"}, {"density 100: must lie between 500 and 6000 kg/m3"}),
        bad_point("mass_too_light", {kNull, kNull, kNull, "10"},
                  {"mass 10: gives a density of 19.1 kg/m3", "must lie between 500 and 6000 kg/m3"}),
        bad_point("unknown_shape", {"cube"}, {"shape cube: use sphere, ellipsoid or box"}),
        bad_point("infinite_velocity", {kNull, kNull, kNull, kNull, "inf"}, {"vx ", "must be a finite number of m/s (the speed at most 100 m/s)"}),
        bad_point("too_fast", {kNull, kNull, kNull, kNull, "90", "90"}, {"vx, vy, vz 90, 90, 0", "at most 100 m/s"}),
        bad_point("release_height_out_of_range", {kNull, kNull, kNull, kNull, kNull, kNull, kNull, "2000"},
                  {"release_height 2000: must lie between 0 and 1000 m"}),
        BadAttribute{"polygon_with_unknown_shape",
                     {kGoodPoint,
                      {"POLYGON((500200 5200000,500300 5200000,500300 5199900,500200 5199900,500200 5200000))", {"cube"}}},
                     {"shape cube: use sphere, ellipsoid or box"}}),
    [](const ::testing::TestParamInfo<BadAttribute>& case_info) { return case_info.param.name; });

}  // namespace
}  // namespace talus
