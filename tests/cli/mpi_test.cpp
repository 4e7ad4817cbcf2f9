// `mpirun -np N talus rockfall|study` (issue 19, item 6; docs/study.md, "More than one
// machine"): the ranks share the rock-fall sources and rank 0 joins their statistics exactly, so
// every layer is bit-identical to one process's for any N; errors are one line, the same exit
// code as one process, and nothing written.
#include <gtest/gtest.h>

#include <fstream>

#include "run_talus.hpp"
#include "same_outputs.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> sample_rockfall(const std::string& out, const std::string& threads) {
  const fs::path sample = test::source_dir() / "sample_dem";
  return {"rockfall", "--dem", (sample / "dem.tif").string(), "--lithology", (sample / "lithology.tif").string(),
          "--vegetation", (sample / "vegetation.tif").string(), "--release", (sample / "rockfall_release.gpkg").string(),
          "--runs", "6", "--seed", "3", "--out", out, "--threads", threads};
}

TEST(Mpi, RockfallLayersAndLinesEqualOneProcessBitForBitForAnyRankCount) {
  const fs::path folder = test::fresh_folder("mpi_rockfall");
  const test::ProgramResult one = test::run_talus(sample_rockfall("one", "2"), folder);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  for (const int ranks : {2, 3}) {
    const std::string out = "ranks" + std::to_string(ranks);
    const test::ProgramResult split = test::run_talus_mpi(ranks, sample_rockfall(out, "1"), folder);
    ASSERT_EQ(split.exit_code, 0) << split.out << split.err;
    EXPECT_NE(split.out.find(std::to_string(ranks) + " MPI ranks x 1 threads"), std::string::npos) << split.out;
    // Rank 0 alone prints: the layers' line once.
    EXPECT_EQ(split.out.find("Layers written"), split.out.rfind("Layers written")) << split.out;
    EXPECT_EQ(test::expect_same_rasters(folder / "one", folder / out), 11);
    const std::vector<std::string> lines = test::trajectory_lines(folder / out);
    EXPECT_GT(lines.size(), 100u);
    EXPECT_EQ(lines, test::trajectory_lines(folder / "one"));
  }
  fs::remove_all(folder);
}

TEST(Mpi, StudyScenariosAndHazardMapEqualOneProcessBitForBit) {
  const fs::path folder = test::fresh_folder("mpi_study");
  const fs::path sample = test::source_dir() / "sample_dem";
  std::ofstream(folder / "study.toml")
      << "[inputs]\ndem = \"" << (sample / "dem.tif").string() << "\"\nlithology = \""
      << (sample / "lithology.tif").string() << "\"\n"
      << "[[rockfall]]\nname = \"blocks\"\nrelease = \"auto\"\nreturn_period = 30\n[rockfall.run]\nruns = 2\n"
      << "[[rockfall]]\nname = \"big-blocks\"\nrelease = \"" << (sample / "rockfall_release.gpkg").string()
      << "\"\nreturn_period = 300\n[rockfall.run]\nruns = 4\n[rockfall.rock]\nsize = \"2\"\n"
      << "[[mudflow]]\nname = \"mud\"\nrelease = \"" << (sample / "mudflow_release.gpkg").string()
      << "\"\nreturn_period = 100\n[mudflow.mud]\nparticle_size = 5\n"
      << "[[mudflow]]\nname = \"deep-mud\"\nrelease = \"" << (sample / "mudflow_release.gpkg").string()
      << "\"\nreturn_period = 300\n[mudflow.mud]\nparticle_size = 5\nrelease_depth = 3.0\n";
  const test::ProgramResult one = test::run_talus({"study", "study.toml", "--out", "one", "--threads", "2"}, folder);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const test::ProgramResult split = test::run_talus_mpi(2, {"study", "study.toml", "--out", "two", "--threads", "1"}, folder);
  ASSERT_EQ(split.exit_code, 0) << split.out << split.err;
  EXPECT_EQ(split.out.find("Study written"), split.out.rfind("Study written")) << split.out;
  // The second mud flow runs on rank 1, beside the first on rank 0.
  EXPECT_NE(split.out.find("runs on MPI rank 1"), std::string::npos) << split.out;
  // Four scenarios' layers, the detected sources, the three hazard maps and the region layers.
  EXPECT_GE(test::expect_same_rasters(folder / "one", folder / "two"), 2 * 11 + 2 * 6 + 1 + 3 + 12);
  EXPECT_TRUE(fs::exists(folder / "two" / "study.json"));
  EXPECT_TRUE(fs::exists(folder / "two" / "hazard" / "hazard_zones.gpkg"));

  // A second run under mpirun resumes: every scenario already done, nothing simulated.
  const test::ProgramResult again = test::run_talus_mpi(2, {"study", "study.toml", "--out", "two", "--threads", "1"}, folder);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(again.out.find("Simulating"), std::string::npos) << again.out;
  std::size_t resumed = 0;
  for (auto at = again.out.find("already done"); at != std::string::npos; at = again.out.find("already done", at + 1)) ++resumed;
  EXPECT_EQ(resumed, 4u) << again.out;  // rank 0 decides for every rank, the mud flow of rank 1 too
  EXPECT_GE(test::expect_same_rasters(folder / "one", folder / "two"), 2 * 11 + 2 * 6 + 1 + 3 + 12);
  fs::remove_all(folder);
}

TEST(Mpi, ABadInputIsOneLineWithExitCodeTwoAndNothingWritten) {
  const fs::path folder = test::fresh_folder("mpi_bad_input");
  std::vector<std::string> arguments = sample_rockfall("out", "1");
  arguments[2] = "missing.tif";
  const test::ProgramResult result = test::run_talus_mpi(2, arguments, folder);
  EXPECT_EQ(result.exit_code, 2) << result.err;
  const std::vector<std::string> errors = test::error_lines(result.err);
  ASSERT_EQ(errors.size(), 1u) << result.err;
  EXPECT_NE(errors.front().find("missing.tif (DEM): file not found"), std::string::npos) << errors.front();
  EXPECT_FALSE(fs::exists(folder / "out"));
  fs::remove_all(folder);
}

TEST(Mpi, AFailingTrajectoryStopsEveryRankWithTheErrorOfOneProcess) {
  const fs::path folder = test::fresh_folder("mpi_failure");
  const fs::path c = test::source_dir() / "validation" / "tschamut2014";
  // Without the recovery, 5 of the 54 trajectories fail: more than [run] failure_share (1 %), so the
  // run fails, naming the first failure of the joined shares (docs/rockfall-full.md, section 5).
  std::ofstream(folder / "failing.toml") << "[full]\nguard_tolerance = 1e-300\nmax_retries = 0\nrestarts = 0\n"
                                            "[run]\nredraws = 0\n";
  const auto arguments = [&](const std::string& threads) {
    return std::vector<std::string>{"rockfall", "--dem", (c / "terrain.asc").string(), "--crs", "local", "--release",
                                    (c / "calibration_runs.vrt").string(), "--materials", (c / "materials.toml").string(),
                                    "--mode", "full", "--runs", "3", "--out", "out", "--scenario", "failing.toml",
                                    "--threads", threads};
  };
  const test::ProgramResult one = test::run_talus(arguments("1"), folder);
  const test::ProgramResult split = test::run_talus_mpi(2, arguments("1"), folder);
  EXPECT_EQ(one.exit_code, 3) << one.err;
  EXPECT_EQ(split.exit_code, 3) << split.err;
  const std::vector<std::string> errors = test::error_lines(split.err);
  ASSERT_EQ(errors.size(), 1u) << split.err;
  EXPECT_EQ(errors, test::error_lines(one.err));
  EXPECT_FALSE(fs::exists(folder / "out"));
  fs::remove_all(folder);
}

TEST(Mpi, CommandsThatDoNotSplitRefuseSeveralRanks) {
  const fs::path folder = test::fresh_folder("mpi_refused");
  const fs::path sample = test::source_dir() / "sample_dem";
  const test::ProgramResult result = test::run_talus_mpi(
      2, {"mudflow", "--dem", (sample / "dem.tif").string(), "--release", (sample / "mudflow_release.gpkg").string(), "--out", "out"},
      folder);
  EXPECT_EQ(result.exit_code, 2);
  const std::vector<std::string> errors = test::error_lines(result.err);
  ASSERT_EQ(errors.size(), 1u) << result.err;
  EXPECT_NE(errors.front().find("talus mudflow runs in one process"), std::string::npos) << errors.front();
  EXPECT_FALSE(fs::exists(folder / "out"));
  fs::remove_all(folder);
}

}  // namespace
}  // namespace talus
