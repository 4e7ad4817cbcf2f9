// `talus rockfall` reports trajectories cut short (issue 17, item 5): rocks stopped by the DEM's
// nodata edge, by the DEM's edge or by the time limit go into run.json's `problems` and onto
// the terminal, one line per cause with its count and share of all rocks; a cause that stopped
// no rock is not reported.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

// A 400 x 300 m slope falling south at 8 m per 10 m cell; with `flat_below` > 0 it levels off
// from that row on (the rocks come to rest), otherwise its lower left quarter is nodata (rocks
// there stop at the nodata edge) and the rest runs out at the DEM's south edge.
void write_scene(const fs::path& folder, int flat_below) {
  test::RasterFixture dem;
  dem.value = [flat_below](int col, int row) {
    if (flat_below > 0) return 1000.0 - 8.0 * std::min(row, flat_below);
    return row >= 20 && col < 20 ? -9999.0 : 1000.0 - 8.0 * row;
  };
  write_raster(folder / "dem.tif", dem);
  test::RasterFixture release;
  release.value = [](int col, int row) { return row == 1 && col >= 5 && col < 35 ? 1.0 : 0.0; };
  write_raster(folder / "release.tif", release);
}

struct RockfallRun {
  test::ProgramResult result;
  nlohmann::json record;
};

// The scene of write_scene(flat_below) in a fresh folder `name`, run with the scenario text.
RockfallRun run_scene(const std::string& name, int flat_below, const std::string& scenario) {
  const auto folder = test::fresh_folder(name);
  write_scene(folder, flat_below);
  std::vector<std::string> arguments = {"rockfall", "--dem", (folder / "dem.tif").string(), "--release",
                                        (folder / "release.tif").string(), "--out", (folder / "out").string(),
                                        "--runs", "4", "--threads", "2"};
  if (!scenario.empty()) {
    std::ofstream(folder / "scenario.toml") << scenario;
    arguments.insert(arguments.end(), {"--scenario", (folder / "scenario.toml").string()});
  }
  RockfallRun run{test::run_talus(arguments, folder), {}};
  std::ifstream in(folder / "out" / "run.json");
  if (in) run.record = nlohmann::json::parse(in);
  return run;
}

// The problem line a cause should give, from run.json's own counts.
std::string expected_line(const nlohmann::json& record, const std::string& reason, const std::string& what) {
  std::uint64_t rocks = 0;
  for (const auto& [name, count] : record["counts"]["stop_reasons"].items()) rocks += count.get<std::uint64_t>();
  const auto count = record["counts"]["stop_reasons"][reason].get<std::uint64_t>();
  char share[64];
  std::snprintf(share, sizeof share, "%.3g", 100.0 * static_cast<double>(count) / static_cast<double>(rocks));
  return "trajectories: " + std::to_string(count) + " of " + std::to_string(rocks) + " rocks (" + share + " %) " + what +
         " (stop reason " + reason + ")";
}

// The line is among run.json's problems and printed as a `problem:` line.
void expect_reported(const RockfallRun& run, const std::string& line) {
  bool recorded = false;
  for (const auto& problem : run.record["problems"]) recorded = recorded || problem.get<std::string>() == line;
  EXPECT_TRUE(recorded) << line << "\nin " << run.record["problems"].dump();
  EXPECT_NE(run.result.out.find("problem: " + line + "\n"), std::string::npos) << run.result.out;
}

std::size_t trajectory_problems(const nlohmann::json& record) {
  std::size_t n = 0;
  for (const auto& problem : record["problems"]) n += problem.get<std::string>().rfind("trajectories: ", 0) == 0;
  return n;
}

const char* const kNodataEdge =
    "stopped where they entered cells without elevation (the DEM's nodata edge); the layers end there, so the area "
    "beyond may be reached too";
const char* const kDemEdge = "left the DEM's extent; the layers end at its edge, so the area beyond may be reached too";

TEST(RockfallProblems, RocksStoppedByTheNodataEdgeAndTheDemEdgeAreReportedWithCountsAndShares) {
  const RockfallRun run = run_scene("rockfall_problems_edges", 0, "");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  const auto& stops = run.record["counts"]["stop_reasons"];
  ASSERT_GT(stops["nodata_area"].get<int>(), 0);
  ASSERT_GT(stops["left_dem"].get<int>(), 0);
  ASSERT_EQ(stops["max_time"].get<int>(), 0);
  expect_reported(run, expected_line(run.record, "nodata_area", kNodataEdge));
  expect_reported(run, expected_line(run.record, "left_dem", kDemEdge));
  EXPECT_EQ(trajectory_problems(run.record), 2u) << "no line for max_time, which stopped no rock";
}

TEST(RockfallProblems, RocksStoppedByTheTimeLimitNameTheParameter) {
  const RockfallRun run = run_scene("rockfall_problems_time", 0, "[fast_bounce]\nmax_time = 1.5\n");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  ASSERT_GT(run.record["counts"]["stop_reasons"]["max_time"].get<int>(), 0);
  expect_reported(run, expected_line(run.record, "max_time",
                                     "were still moving at the time limit ([fast_bounce] max_time = 1.5 s); the layers "
                                     "miss the rest of their paths: raise [fast_bounce] max_time"));
}

TEST(RockfallProblems, NothingIsReportedWhenEveryRockComesToRest) {
  const RockfallRun run = run_scene("rockfall_problems_none", 12, "");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  const auto& stops = run.record["counts"]["stop_reasons"];
  ASSERT_EQ(stops["at_rest"].get<int>(), run.record["counts"]["trajectories"].get<int>());
  EXPECT_EQ(trajectory_problems(run.record), 0u) << run.record["problems"].dump();
  EXPECT_EQ(run.result.out.find("problem: trajectories"), std::string::npos) << run.result.out;
}

}  // namespace
}  // namespace talus
