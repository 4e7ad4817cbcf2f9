// Regions larger than memory (issue 19, item 4; docs/study.md, "Tiles"): a rock fall run in
// tiles writes the layers and lines of the untiled run bit for bit when no rock reaches a halo's
// edge, alone and under MPI; rocks that do reach it are counted and reported; a budget too small
// for the region is one line, exit code 2, and nothing written.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "run_talus.hpp"
#include "same_outputs.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> sample_rockfall(const std::string& out, std::vector<std::string> extra) {
  const fs::path sample = test::source_dir() / "sample_dem";
  std::vector<std::string> arguments = {
      "rockfall", "--dem", (sample / "dem.tif").string(), "--lithology", (sample / "lithology.tif").string(),
      "--vegetation", (sample / "vegetation.tif").string(), "--release", (sample / "rockfall_release.gpkg").string(),
      "--runs", "8", "--seed", "5", "--project", "off", "--out", out};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return arguments;
}

nlohmann::json run_record(const fs::path& out) {
  std::ifstream in(out / "run.json");
  return nlohmann::json::parse(in);
}

TEST(Tiles, TiledLayersAndLinesEqualTheUntiledRunBitForBitWhenNoRockReachesAHaloEdge) {
  const fs::path folder = test::fresh_folder("tiles_equal");
  const test::ProgramResult whole = test::run_talus(sample_rockfall("whole", {"--threads", "2"}), folder);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_TRUE(run_record(folder / "whole")["tiles"].is_null());
  // 30 x 30 cell tiles with a halo wider than any runout of the scene: every tile's rocks stay on it.
  const test::ProgramResult tiled =
      test::run_talus(sample_rockfall("tiled", {"--threads", "2", "--tile-size", "30", "--halo", "1500"}), folder);
  ASSERT_EQ(tiled.exit_code, 0) << tiled.err;
  EXPECT_NE(tiled.out.find("Tiles: "), std::string::npos) << tiled.out;
  const nlohmann::json record = run_record(folder / "tiled");
  EXPECT_GT(record["tiles"]["tiles"].get<int>(), 20);
  EXPECT_EQ(record["counts"]["stop_reasons"]["tile_edge"].get<int>(), 0);
  EXPECT_EQ(test::expect_same_rasters(folder / "whole", folder / "tiled"), 11);
  const std::vector<std::string> lines = test::trajectory_lines(folder / "tiled");
  EXPECT_GT(lines.size(), 100u);
  EXPECT_EQ(lines, test::trajectory_lines(folder / "whole"));
  // The same under MPI: two ranks, each with its share of every tile's sources.
  const test::ProgramResult ranks =
      test::run_talus_mpi(2, sample_rockfall("ranks", {"--threads", "1", "--tile-size", "30", "--halo", "1500"}), folder);
  ASSERT_EQ(ranks.exit_code, 0) << ranks.out << ranks.err;
  EXPECT_EQ(test::expect_same_rasters(folder / "whole", folder / "ranks"), 11);
  EXPECT_EQ(test::trajectory_lines(folder / "ranks"), lines);
  fs::remove_all(folder);
}

TEST(Tiles, RocksThatReachAHaloEdgeAreCountedAndReported) {
  const fs::path folder = test::fresh_folder("tiles_halo");
  const test::ProgramResult tiled =
      test::run_talus(sample_rockfall("tiled", {"--tile-size", "40", "--halo", "50"}), folder);
  ASSERT_EQ(tiled.exit_code, 0) << tiled.err;
  const nlohmann::json record = run_record(folder / "tiled");
  const auto stopped = record["counts"]["stop_reasons"]["tile_edge"].get<std::uint64_t>();
  EXPECT_GT(stopped, 0u);
  EXPECT_EQ(record["tiles"]["halo_m"].get<double>(), 50.0);
  bool reported = false;
  for (const auto& line : record["problems"]) {
    const std::string text = line.get<std::string>();
    if (text.find("stop reason tile_edge") != std::string::npos) {
      reported = true;
      EXPECT_NE(text.find(std::to_string(stopped) + " of "), std::string::npos) << text;
      EXPECT_NE(text.find("[tiles] halo = 50 m"), std::string::npos) << text;
      EXPECT_NE(tiled.out.find(text), std::string::npos) << tiled.out;
    }
  }
  EXPECT_TRUE(reported) << record["problems"].dump();
  EXPECT_NE(tiled.out.find("tile_edge " + std::to_string(stopped)), std::string::npos) << tiled.out;
  fs::remove_all(folder);
}

TEST(Tiles, AMemoryBudgetTooSmallForTheRegionIsOneLineAndNothingWritten) {
  const fs::path folder = test::fresh_folder("tiles_memory");
  const test::ProgramResult small = test::run_talus(sample_rockfall("out", {"--memory", "0.1"}), folder);
  EXPECT_EQ(small.exit_code, 2) << small.out << small.err;
  EXPECT_NE(small.err.find("--memory 0.1 GB"), std::string::npos) << small.err;
  EXPECT_FALSE(fs::exists(folder / "out"));
  fs::remove_all(folder);
}

}  // namespace
}  // namespace talus
