// Parameters against their ranges (issue 18, item 1): every number of `talus params` (rock fall,
// mud flow, the materials file's classes) that has a range carries it in the JSON, and a value
// outside it, from a scenario file or a flag, is refused before any work with one line naming the
// key or flag, the value and the range. More refusals, kind by kind: bad_input_kinds_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> sample(const fs::path& out, std::vector<std::string> extra) {
  const auto dem = test::source_dir() / "sample_dem";
  std::vector<std::string> arguments = {"rockfall", "--dem", (dem / "dem.tif").string(), "--release",
                                        (dem / "rockfall_release.gpkg").string(), "--out", out.string(), "--runs", "2"};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return arguments;
}

TEST(ParameterRanges, TalusParamsCarriesTheRangesAndEveryDefaultLiesInItsRange) {
  const auto work = test::fresh_folder("parameter_ranges_params");
  const auto result = test::run_talus({"params"}, work);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto all = nlohmann::json::parse(result.out);
  // The fewest ranged numbers of each list: every number it has but the seed.
  const std::pair<const char*, int> lists[] = {{"rockfall", 48}, {"mudflow", 32}, {"materials", 10}};
  for (const auto& [list, fewest] : lists) {
    int with_range = 0;
    for (const auto& p : all[list]) {
      if (!p.contains("range")) continue;
      ++with_range;
      const auto& r = p["range"];
      if (!p.contains("default")) continue;  // a materials field: each class gives its own
      const double value = p["default"].is_number() ? p["default"].get<double>() : r["min"].get<double>() + 1;
      if (r.contains("off") && value == r["off"].get<double>()) continue;  // "0 (all cores)"
      EXPECT_TRUE(r["min_exclusive"] ? value > r["min"].get<double>() : value >= r["min"].get<double>())
          << list << " " << p["section"] << " " << p["name"] << ": the default lies below its range";
      EXPECT_TRUE(r["max_exclusive"] ? value < r["max"].get<double>() : value <= r["max"].get<double>())
          << list << " " << p["section"] << " " << p["name"] << ": the default lies above its range";
    }
    EXPECT_GE(with_range, fewest) << list;
  }
  const auto& rockfall = all["rockfall"];
  const auto gravity = std::find_if(rockfall.begin(), rockfall.end(), [](const nlohmann::json& p) {
    return p["section"] == "fast_bounce" && p["name"] == "gravity";
  });
  ASSERT_NE(gravity, rockfall.end());
  EXPECT_EQ((*gravity)["range"], nlohmann::json({{"min", 0.1}, {"max", 100.0}, {"min_exclusive", false}, {"max_exclusive", false}}));
  const auto& mudflow = all["mudflow"];
  const auto depth = std::find_if(mudflow.begin(), mudflow.end(), [](const nlohmann::json& p) {
    return p["section"] == "mud" && p["name"] == "release_depth";
  });
  ASSERT_NE(depth, mudflow.end());
  EXPECT_EQ((*depth)["range"]["off"], 0.0);
  EXPECT_EQ((*depth)["range"]["off_means"], "the release file's depths");
}

TEST(ParameterRanges, RockfallValuesOutsideTheirRangesAreRefusedBeforeAnyWork) {
  const auto root = test::fresh_folder("rockfall_ranges_refused");
  struct Case {
    std::string scenario;  // TOML; empty: `flags` only
    std::vector<std::string> flags;
    std::string message;
  };
  const std::vector<Case> cases = {
      // Values that once made a run hang.
      {"[fast_bounce]\nmax_step_length = 1e-9\n", {}, "[fast_bounce] max_step_length 1e-09: expected 0.001-100 m"},
      {"[full]\ncarpet_spacing = 1e-300\n", {}, "[full] carpet_spacing 1e-300: expected 0.01-1"},
      {"[fast_bounce]\ncontact_tolerance = -0.0\n", {}, "[fast_bounce] contact_tolerance -0: expected 0.0001-10 m"},
      // Values that once gave all-zero or negative maps.
      {"[fast_bounce]\nsample_spacing = 0\n", {}, "[fast_bounce] sample_spacing 0: expected 0.01-1000 m"},
      // Misreported before: the scenario's key is named, not a flag.
      {"", {"--density", "50"}, "--density 50: expected 500-6000 kg/m3"},
      // Integers that would wrap around.
      {"[full]\nmax_retries = 4294967297\n", {}, "[full] max_retries must be a non-negative integer of at most 2147483647"},
      {"[stochastic]\nnoise_octaves = -1\n", {}, "[stochastic] noise_octaves must be a non-negative integer"},
      {"[run]\nsaved_trajectories = 1e9\n", {}, "[run] saved_trajectories 1000000000: expected 0-10000000"},
  };
  int k = 0;
  for (const Case& c : cases) {
    std::vector<std::string> flags = c.flags;
    if (!c.scenario.empty()) {
      const auto file = root / ("case" + std::to_string(k) + ".toml");
      std::ofstream(file) << c.scenario;
      flags.insert(flags.end(), {"--scenario", file.string()});
    }
    const auto out = root / ("out" + std::to_string(k++));
    const auto result = test::run_talus(sample(out, flags), root);
    EXPECT_EQ(result.exit_code, 2) << c.message << "\n" << result.err;
    EXPECT_EQ(result.err.rfind("talus: error: ", 0), 0u) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_NE(result.err.find(c.message), std::string::npos) << result.err;
    EXPECT_EQ(result.out.find("Simulating"), std::string::npos) << "refused only after work: " << c.message;
    EXPECT_FALSE(fs::exists(out)) << c.message;
  }
}

}  // namespace
}  // namespace talus
