// A trajectory that fails numerically (issue 16, Deliver 1; docs/rockfall-full.md, section 5,
// "When a trajectory fails"): the run stops with exit code 3 and writes nothing; its one error
// line names the source and run and gives the command that reruns that trajectory alone, which
// fails the same way. --only-source and --only-run select exactly those runs.
#include <gtest/gtest.h>

#include <ogrsf_frmts.h>

#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "run_talus.hpp"
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
    // A guard that hardly any step can pass, without retries: the trajectories fail (a negative
    // tolerance, which no step passed, is now refused by its range).
    std::ofstream(root_ / "failing.toml") << "[full]\nguard_tolerance = 1e-300\nmax_retries = 0\n";
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

TEST_F(RockfallFailure, StopsWritesNothingAndNamesTheCommandThatReproducesIt) {
  std::vector<std::string> arguments = case_arguments(root_ / "out");
  arguments.insert(arguments.end(), {"--scenario", (root_ / "failing.toml").string()});
  const test::ProgramResult result = test::run_talus(arguments, root_);
  EXPECT_EQ(result.exit_code, 3) << result.err;
  const std::vector<std::string> errors = test::error_lines(result.err);
  ASSERT_EQ(errors.size(), 1u) << result.err;
  const std::string& line = errors.front();
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
  EXPECT_EQ(again_errors.front(), line);
  EXPECT_FALSE(fs::exists(root_ / "out"));
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
