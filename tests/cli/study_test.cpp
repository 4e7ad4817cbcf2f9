// `talus study` (issue 19, items 1-2; docs/study.md): every scenario of a study file runs as its
// subcommand would, into its own folder, with layers bit-identical to the subcommand's own run;
// study.json records each scenario; a bad study file or a bad input of any scenario is refused
// with one line, exit code 2 and nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

// A study of the sample scene: one small block scenario and one mud flow, 5 m particles.
std::string sample_study(const std::string& extra_rockfall_key = "", const std::string& mudflow_release = "") {
  const fs::path sample = test::source_dir() / "sample_dem";
  const std::string mud_release = mudflow_release.empty() ? (sample / "mudflow_release.gpkg").string() : mudflow_release;
  return "[inputs]\n"
         "dem = \"" + (sample / "dem.tif").string() + "\"\n"
         "lithology = \"" + (sample / "lithology.tif").string() + "\"\n"
         "vegetation = \"" + (sample / "vegetation.tif").string() + "\"\n"
         "[[rockfall]]\n"
         "name = \"blocks\"\n"
         "release = \"" + (sample / "rockfall_release.gpkg").string() + "\"\n"
         "return_period = 30\n" + extra_rockfall_key +
         "[rockfall.run]\nruns = 3\nseed = 7\n"
         "[rockfall.rock]\nsize = \"0.8\"\n"
         "[rockfall.outputs]\nproject = \"off\"\n"
         "[[mudflow]]\n"
         "name = \"mud\"\n"
         "release = \"" + mud_release + "\"\n"
         "annual_frequency = 0.01\n"
         "[mudflow.mud]\nparticle_size = 5\n"
         "[mudflow.outputs]\nproject = \"off\"\n";
}

fs::path write_study(const fs::path& folder, const std::string& text) {
  const fs::path file = folder / "study.toml";
  std::ofstream(file) << text;
  return file;
}

std::vector<float> band(const fs::path& path) { return test::read_band(path); }

TEST(Study, EachScenarioEqualsItsSubcommandBitForBit) {
  const fs::path folder = test::fresh_folder("study_equal");
  const fs::path study = write_study(folder, sample_study());
  const test::ProgramResult run = test::run_talus({"study", study.string(), "--out", "out", "--threads", "2"}, folder);
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.err.find("study: about"), std::string::npos) << run.err;  // the time left over the whole study

  const fs::path sample = test::source_dir() / "sample_dem";
  const std::vector<std::string> scene = {"--dem", (sample / "dem.tif").string(), "--lithology",
                                          (sample / "lithology.tif").string(), "--vegetation",
                                          (sample / "vegetation.tif").string()};
  std::vector<std::string> rockfall = {"rockfall", "--release", (sample / "rockfall_release.gpkg").string(), "--out",
                                       "rockfall", "--runs", "3", "--seed", "7", "--block-size", "0.8", "--threads", "1"};
  rockfall.insert(rockfall.end(), scene.begin(), scene.end());
  std::vector<std::string> mudflow = {"mudflow", "--release", (sample / "mudflow_release.gpkg").string(), "--out",
                                      "mudflow", "--particle-size", "5", "--threads", "1"};
  mudflow.insert(mudflow.end(), scene.begin(), scene.end());
  ASSERT_EQ(test::run_talus(rockfall, folder).exit_code, 0);
  ASSERT_EQ(test::run_talus(mudflow, folder).exit_code, 0);

  for (const char* layer : {"reach_probability", "energy_max", "passages", "deposits", "intensity"}) {
    EXPECT_EQ(band(folder / "out/scenarios/blocks" / (std::string(layer) + ".tif")),
              band(folder / "rockfall" / (std::string(layer) + ".tif")))
        << layer;
  }
  for (const char* layer : {"flow_depth_max", "velocity_max", "deposit_depth", "arrival_time", "intensity"}) {
    EXPECT_EQ(band(folder / "out/scenarios/mud" / (std::string(layer) + ".tif")),
              band(folder / "mudflow" / (std::string(layer) + ".tif")))
        << layer;
  }
  EXPECT_EQ(test::check_layers("rockfall", folder / "out/scenarios/blocks", sample / "dem.tif"), 0);
  EXPECT_EQ(test::check_layers("mudflow", folder / "out/scenarios/mud", sample / "dem.tif"), 0);

  std::ifstream record_file(folder / "out/study.json");
  const nlohmann::json record = nlohmann::json::parse(record_file);
  ASSERT_EQ(record["scenarios"].size(), 2u);
  EXPECT_EQ(record["scenarios"][0]["name"], "blocks");
  EXPECT_EQ(record["scenarios"][0]["process"], "rockfall");
  EXPECT_DOUBLE_EQ(record["scenarios"][0]["return_period_years"].get<double>(), 30.0);
  EXPECT_EQ(record["scenarios"][0]["parameters"]["run"]["seed"], 7);
  EXPECT_EQ(record["scenarios"][0]["counts"]["trajectories"], 3 * 260);
  EXPECT_DOUBLE_EQ(record["scenarios"][1]["return_period_years"].get<double>(), 100.0);
  EXPECT_EQ(record["scenarios"][1]["folder"], "scenarios/mud");
}

// Each bad study is refused before any scenario runs: one line naming the file and the key,
// exit code 2, no output folder.
TEST(Study, ABadStudyIsRefusedWithOneLineAndNothingWritten) {
  const fs::path folder = test::fresh_folder("study_bad");
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {sample_study("blocks = 3\n"), "unknown key 'blocks'"},
      {sample_study("[rockfall.fast_bounce]\nmax_step_length = 1e-9\n"), "[fast_bounce] max_step_length"},
      {sample_study("[rockfall.mud]\nparticle_size = 5\n"), "unknown section [mud]"},
      {sample_study("", (folder / "missing.gpkg").string()), "missing.gpkg"},
      {sample_study() + "[[mudflow]]\nname = \"mud\"\nrelease = \"r.gpkg\"\nreturn_period = 10\n", "a second scenario"},
      {"[inputs]\ndem = \"dem.tif\"\n", "no scenario"},
  };
  for (const auto& c : cases) {
    const fs::path study = write_study(folder, c.text);
    const test::ProgramResult run = test::run_talus({"study", study.string(), "--out", "out"}, folder);
    EXPECT_EQ(run.exit_code, 2) << c.expected << "\n" << run.out << run.err;
    EXPECT_NE(run.err.find(c.expected), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(fs::exists(folder / "out")) << c.expected;
  }
}

}  // namespace
}  // namespace talus
