// Trajectories that fail numerically (issue 16, Deliver 1; issue 38, item 7; docs/rockfall-full.md,
// section 5, "Recovery"): below [run] failure_share the run goes on, records each
// failure in run.json and a problem line, and its layers say how many trajectories they miss, the
// same at any thread count; above it the run ends with exit code 3 and writes nothing, and its one
// error line names the first failure and gives the command that reruns that trajectory alone,
// which fails the same way. --only-source and --only-run select exactly those runs.
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "run_talus.hpp"
#include "same_outputs.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

// The Tschamut 2014 release points on their terrain, 3 runs per point, in `mode`.
std::vector<std::string> case_arguments(const fs::path& out, const std::string& mode = "full") {
  const fs::path c = test::source_dir() / "validation" / "tschamut2014";
  return {"rockfall", "--dem", (c / "terrain.asc").string(), "--crs", "local", "--release",
          (c / "calibration_runs.vrt").string(), "--materials", (c / "materials.toml").string(), "--mode", mode,
          "--runs", "3", "--out", out.string()};
}

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream in(text);
  for (std::string word; in >> word;) result.push_back(word);
  return result;
}

class RockfallFailure : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_folder("rockfall_failure");
    // A guard that hardly any step that gains energy can pass, without retries or recovery: 5 of
    // the 54 trajectories fail, the first of them source 0, run 0 (a negative tolerance, which no
    // step passed, is refused by its range).
    std::ofstream(root_ / "failing.toml") << "[full]\nguard_tolerance = 1e-300\nmax_retries = 0\nrestarts = 0\n"
                                             "[run]\nredraws = 0\n";
  }
  // A guard that a few steps fail (2 of the 54 trajectories at seed 1), without retries or
  // recovery, and the failure share given.
  fs::path some_failing(double failure_share) const {
    const fs::path path = root_ / ("some_failing_" + std::to_string(failure_share) + ".toml");
    std::ofstream(path) << "[full]\nguard_tolerance = 1e-4\nmax_retries = 0\nrestarts = 0\n"
                           "[run]\nredraws = 0\nfailure_share = " << failure_share << "\n";
    return path;
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

TEST_F(RockfallFailure, AboveTheShareStopsWritesNothingAndNamesTheCommandThatReproducesIt) {
  std::vector<std::string> arguments = case_arguments(root_ / "out");
  arguments.insert(arguments.end(), {"--scenario", (root_ / "failing.toml").string()});
  const test::ProgramResult result = test::run_talus(arguments, root_);
  EXPECT_EQ(result.exit_code, 3) << result.err;
  const std::vector<std::string> errors = test::error_lines(result.err);
  ASSERT_EQ(errors.size(), 1u) << result.err;
  const std::string& line = errors.front();
  EXPECT_NE(line.find(" of 54 trajectories ("), std::string::npos) << line;
  EXPECT_NE(line.find("failed numerically, more than [run] failure_share = 1 %"), std::string::npos) << line;
  EXPECT_NE(line.find("blow-up not recovered by smaller steps"), std::string::npos) << line;
  EXPECT_NE(line.find("(source 0, run 0)"), std::string::npos) << line;
  EXPECT_NE(line.find("nothing was written"), std::string::npos) << line;
  EXPECT_FALSE(fs::exists(root_ / "out"));

  // The command it gives reruns that one trajectory, which fails the same way.
  const std::string marker = "to rerun that trajectory alone: ";
  const std::size_t at = line.find(marker);
  ASSERT_NE(at, std::string::npos) << line;
  std::vector<std::string> rerun = words(line.substr(at + marker.size()));
  ASSERT_GT(rerun.size(), 4u);
  EXPECT_EQ(std::vector<std::string>(rerun.end() - 4, rerun.end()),
            (std::vector<std::string>{"--only-source", "0", "--only-run", "0"}));
  rerun.erase(rerun.begin());  // the program's path: run_talus adds the built one
  const test::ProgramResult again = test::run_talus(rerun, root_);
  EXPECT_EQ(again.exit_code, 3) << again.err;
  const std::vector<std::string> again_errors = test::error_lines(again.err);
  ASSERT_EQ(again_errors.size(), 1u) << again.err;
  const auto first = [](const std::string& text) { return text.substr(text.find("the first: ")); };
  EXPECT_NE(again_errors.front().find(": 1 of 1 trajectories (100 %)"), std::string::npos) << again_errors.front();
  EXPECT_EQ(first(again_errors.front()), first(line));
  EXPECT_FALSE(fs::exists(root_ / "out"));
}

// A layer's metadata item (GDAL).
std::string layer_metadata(const fs::path& tif, const char* key) {
  GDALAllRegister();
  GDALDatasetUniquePtr data(GDALDataset::Open(tif.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  const char* value = data ? data->GetMetadataItem(key) : nullptr;
  return value != nullptr ? value : "";
}

// Below the share the run goes on: exit code 0, each failure in run.json (source, run, time,
// place, reason) and in a problem line, the layers without them and saying so (metadata and QGIS
// abstract), and the same layers at 1 and 2 threads. A share just below the run's fails it.
TEST_F(RockfallFailure, BelowTheShareTheRunGoesOnRecordsTheFailuresAndTheLayersSayWhatTheyMiss) {
  std::vector<test::ProgramResult> results;
  for (const std::string threads : {"1", "2"}) {
    std::vector<std::string> arguments = case_arguments(root_ / ("threads" + threads));
    arguments.insert(arguments.end(), {"--scenario", some_failing(50.0).string(), "--threads", threads});
    results.push_back(test::run_talus(arguments, root_));
    ASSERT_EQ(results.back().exit_code, 0) << results.back().err;
  }
  std::ifstream file(root_ / "threads1" / "run.json");
  const nlohmann::json record = nlohmann::json::parse(file);
  const nlohmann::json& recovery = record["recovery"];
  const std::uint64_t failed = recovery["failed"];
  ASSERT_GT(failed, 0u);
  ASSERT_LT(failed, 54u);
  EXPECT_EQ(record["counts"]["failed_trajectories"], failed);
  EXPECT_EQ(record["counts"]["trajectories"], 54u - failed);
  EXPECT_EQ(recovery["failure_share_percent"], 50.0);
  ASSERT_EQ(recovery["failures"].size(), failed);
  for (const nlohmann::json& f : recovery["failures"]) {
    EXPECT_LT(f["source"].get<int>(), 18);
    EXPECT_LT(f["run"].get<int>(), 3);
    EXPECT_GT(f["time_s"].get<double>(), 0.0);
    EXPECT_TRUE(f["x_m"].is_number() && f["y_m"].is_number() && f["z_m"].is_number()) << f;
    EXPECT_EQ(f["reason"], "blow-up not recovered by smaller steps");
  }
  std::size_t problem_lines = 0;
  std::istringstream out(results.front().out);
  for (std::string line; std::getline(out, line);) {
    if (line.rfind("problem: trajectory failed numerically", 0) == 0) ++problem_lines;
  }
  EXPECT_EQ(problem_lines, failed) << results.front().out;
  EXPECT_NE(results.front().out.find(std::to_string(failed) + " of 54 (" ), std::string::npos) << results.front().out;
  for (const char* layer : {"reach_probability", "energy_max", "deposits"}) {
    const fs::path tif = root_ / "threads1" / (std::string(layer) + ".tif");
    EXPECT_EQ(layer_metadata(tif, "TALUS_MISSING_TRAJECTORIES"), std::to_string(failed)) << layer;
    EXPECT_EQ(layer_metadata(tif, "TALUS_TRAJECTORIES"), "54") << layer;
    const std::string qmd = test::file_bytes(root_ / "threads1" / (std::string(layer) + ".qmd"));
    EXPECT_NE(qmd.find("Missing: " + std::to_string(failed) + " of the run&apos;s 54 trajectories"), std::string::npos)
        << layer;
  }
  EXPECT_GT(test::expect_same_rasters(root_ / "threads1", root_ / "threads2"), 5);
  EXPECT_EQ(test::trajectory_lines(root_ / "threads1"), test::trajectory_lines(root_ / "threads2"));

  const double share = recovery["failed_percent"];
  std::vector<std::string> arguments = case_arguments(root_ / "above");
  arguments.insert(arguments.end(), {"--scenario", some_failing(0.5 * share).string()});
  const test::ProgramResult above = test::run_talus(arguments, root_);
  EXPECT_EQ(above.exit_code, 3) << above.err;
  EXPECT_FALSE(fs::exists(root_ / "above"));
}

// The (source, run) -> runout length (m) of every line of a run's trajectories.gpkg.
std::map<std::pair<long long, long long>, double> line_lengths(const fs::path& out) {
  GDALAllRegister();
  GDALDatasetUniquePtr data(GDALDataset::Open((out / "trajectories.gpkg").c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  std::map<std::pair<long long, long long>, double> lengths;
  if (!data) return lengths;
  for (auto& feature : *data->GetLayerByName("trajectories")) {
    lengths[{feature->GetFieldAsInteger64("source_id"), feature->GetFieldAsInteger64("run_id")}] =
        feature->GetFieldAsDouble("runout_length_m");
  }
  return lengths;
}

// The one trajectory --only-source 7 --only-run 2 simulates is that of the whole run, bit for bit.
TEST_F(RockfallFailure, OnlySourceAndOnlyRunSelectOneTrajectoryOfTheWholeRun) {
  for (const std::string mode : {"fast", "full"}) {
    const std::vector<std::string> whole = case_arguments(root_ / (mode + "-all"), mode);
    std::vector<std::string> one = case_arguments(root_ / (mode + "-one"), mode);
    one.insert(one.end(), {"--only-source", "7", "--only-run", "2"});
    for (const auto& arguments : {whole, one}) {
      const test::ProgramResult result = test::run_talus(arguments, root_);
      ASSERT_EQ(result.exit_code, 0) << result.err;
    }
    std::ifstream file(root_ / (mode + "-one") / "run.json");
    const nlohmann::json record = nlohmann::json::parse(file);
    EXPECT_EQ(record["counts"]["trajectories"], 1) << mode;
    const auto all = line_lengths(root_ / (mode + "-all"));
    const auto single = line_lengths(root_ / (mode + "-one"));
    ASSERT_EQ(single.size(), 1u) << mode;
    EXPECT_EQ(single.begin()->first, (std::pair<long long, long long>{7, 2})) << mode;
    ASSERT_EQ(all.count({7, 2}), 1u) << mode;
    EXPECT_EQ(single.begin()->second, all.at({7, 2})) << mode;
    EXPECT_GT(single.begin()->second, 0.0) << mode;
  }
}

// Beyond the run's sources or runs, negative (not wrapped to 2^64 - 1) or not whole: refused.
TEST_F(RockfallFailure, OnlySourceOrRunBeyondTheRunIsRefused) {
  for (const auto& [flag, value] :
       {std::pair{"--only-source", "18"}, {"--only-run", "3"}, {"--only-run", "-1"}, {"--only-source", "2.5"}}) {
    std::vector<std::string> arguments = case_arguments(root_ / "refused");
    arguments.insert(arguments.end(), {flag, value});
    const test::ProgramResult result = test::run_talus(arguments, root_);
    EXPECT_EQ(result.exit_code, 2) << flag;
    const std::vector<std::string> errors = test::error_lines(result.err);
    ASSERT_EQ(errors.size(), 1u) << result.err;
    EXPECT_NE(errors.front().find(flag), std::string::npos) << errors.front();
    EXPECT_FALSE(fs::exists(root_ / "refused"));
  }
}

}  // namespace
}  // namespace talus
