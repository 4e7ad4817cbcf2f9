// intensity.tif (issue 17, item 3; docs/hazard-statistics.md, "Intensity classes"): the FOEN 2016
// classes by default, recomputed here from the run's own energy_p95; a user's guideline file
// with its own layers, alternatives and products; none; bad guideline files refused before any
// work with one line naming the file, exit code 2 and nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> rockfall_arguments(const fs::path& out, std::vector<std::string> extra = {}) {
  const auto sample = test::source_dir() / "sample_dem";
  std::vector<std::string> arguments = {"rockfall", "--dem", (sample / "dem.tif").string(), "--lithology",
                                        (sample / "lithology.tif").string(), "--release",
                                        (sample / "rockfall_release.gpkg").string(), "--out", out.string(),
                                        "--runs", "3", "--threads", "2"};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return arguments;
}

nlohmann::json run_record(const fs::path& out) {
  std::ifstream in(out / "run.json");
  return nlohmann::json::parse(in);
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream file(path);
  file << text;
}

TEST(Intensity, DefaultIsFoen2016ByTheEnergyPercentileAndCountedInRunJson) {
  const auto root = test::fresh_folder("intensity_default");
  const auto result = test::run_talus(rockfall_arguments(root / "out"), root);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::vector<float> energy = test::read_band(root / "out" / "energy_p95.tif");
  const std::vector<float> intensity = test::read_band(root / "out" / "intensity.tif");
  ASSERT_EQ(energy.size(), intensity.size());
  std::map<float, long> cells;
  for (std::size_t i = 0; i < energy.size(); ++i) {
    const float e = energy[i];
    const float expected = e == -9999.0f ? -9999.0f : e > 300 ? 3.0f : e > 30 ? 2.0f : e > 0 ? 1.0f : 0.0f;
    ASSERT_EQ(intensity[i], expected) << "cell " << i << ", energy_p95 " << e << " kJ";
    ++cells[expected];
  }
  EXPECT_GT(cells[3.0f], 0);
  EXPECT_GT(cells[2.0f], 0);
  const nlohmann::json entry = run_record(root / "out")["intensity"];
  EXPECT_EQ(entry["guideline"], "foen-2016");
  ASSERT_EQ(entry["classes"].size(), 3u);
  for (const auto& c : entry["classes"]) {
    EXPECT_EQ(c["cells"].get<long>(), cells[c["value"].get<float>()]) << c["name"];
    EXPECT_NEAR(c["area_km2"].get<double>(), c["cells"].get<double>() * 25.0 / 1e6, 1e-12);  // 5 m cells
  }
  EXPECT_NE(result.out.find("Intensity (foen-2016): strong " + std::to_string(cells[3.0f]) + " cells"),
            std::string::npos)
      << result.out;
  EXPECT_TRUE(fs::exists(root / "out" / "intensity.qml"));
}

TEST(Intensity, AGuidelineFileSetsItsOwnClassesLayersAndProducts) {
  const auto root = test::fresh_folder("intensity_file");
  const auto guideline = root / "speeds.toml";
  write_file(guideline, R"(
[speeds]
title = "Speed classes"
source = "a test"
[[speeds.rockfall]]
value = 5
name = "fast and frequent"
colour = "#ff0000"
when = ["velocity_max > 20 and passages >= 3", "velocity_max * passages > 200"]
[[speeds.rockfall]]
value = 1
name = "reached"
colour = "#00ff00"
when = ["passages > 0"]
)");
  const auto result = test::run_talus(rockfall_arguments(root / "out", {"--intensity", guideline.string()}), root);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::vector<float> speed = test::read_band(root / "out" / "velocity_max.tif");
  const std::vector<float> passages = test::read_band(root / "out" / "passages.tif");
  const std::vector<float> intensity = test::read_band(root / "out" / "intensity.tif");
  int fast = 0;
  for (std::size_t i = 0; i < speed.size(); ++i) {
    if (speed[i] == -9999.0f) continue;
    const bool strong = (speed[i] > 20 && passages[i] >= 3) || double(speed[i]) * double(passages[i]) > 200;
    const float expected = strong ? 5.0f : passages[i] > 0 ? 1.0f : 0.0f;
    ASSERT_EQ(intensity[i], expected) << "cell " << i;
    fast += strong;
  }
  EXPECT_GT(fast, 0);
  EXPECT_EQ(run_record(root / "out")["intensity"]["guideline"], "speeds");
}

TEST(Intensity, NoneWritesNoIntensityLayer) {
  const auto root = test::fresh_folder("intensity_none");
  const auto result = test::run_talus(rockfall_arguments(root / "out", {"--intensity", "none"}), root);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_FALSE(fs::exists(root / "out" / "intensity.tif"));
  EXPECT_FALSE(run_record(root / "out").contains("intensity"));
}

TEST(Intensity, BadGuidelinesAreRefusedBeforeAnyWorkWithOneLine) {
  const auto root = test::fresh_folder("intensity_bad");
  const std::string head = "[g]\n[[g.rockfall]]\nvalue = 1\nname = \"x\"\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {head + "colour = \"red\"\nwhen = [\"energy_max > 1\"]\n", "`colour` must be #rrggbb"},
      {head + "colour = \"#ff0000\"\nwhen = [\"energy_max > many\"]\n", "is not a finite number"},
      {head + "colour = \"#ff0000\"\nwhen = [\"flow_depth_max > 1\"]\n", "'flow_depth_max', which rockfall does not write"},
      {"[g]\ntitle = \"no classes\"\n", "has no [[g.rockfall]] classes"},
      {"[g\n", "(intensity guideline): line 1"}};
  int k = 0;
  for (const auto& [text, message] : cases) {
    const auto file = root / ("bad" + std::to_string(k++) + ".toml");
    write_file(file, text);
    const auto out = root / ("out" + std::to_string(k));
    const auto result = test::run_talus(rockfall_arguments(out, {"--intensity", file.string()}), root);
    EXPECT_EQ(result.exit_code, 2) << text;
    EXPECT_NE(result.err.find(message), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(file.string()), std::string::npos) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_EQ(result.out.find("Simulating"), std::string::npos) << "refused only after work: " << result.out;
    EXPECT_FALSE(fs::exists(out)) << "left " << out;
  }
  const auto unknown = test::run_talus(rockfall_arguments(root / "out_unknown", {"--intensity", "swiss"}), root);
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("--intensity swiss: not a built-in guideline (foen-2016)"), std::string::npos)
      << unknown.err;
}

}  // namespace
}  // namespace talus
