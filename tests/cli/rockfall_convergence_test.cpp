// `talus rockfall` and the convergence of its maps (issue 17, items 2 and 5; docs/hazard-statistics.md,
// "Convergence"): --runs auto records the runs of every source in run.json, converges within the
// tolerance and gives the same layers at 1 and 2 threads; a source that ends at N runs has the
// layers of --runs N; too few fixed runs are a problem, in run.json and on the terminal, that
// names the runs needed; bad run settings are refused with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

const char* const kLayers[] = {"reach_probability", "passages", "source_count", "deposits", "energy_max",
                               "energy_p95", "jump_height_p95", "velocity_max", "energy_loss_friction",
                               "energy_loss_deformation"};

// Auto with a small first batch and limit, so that the tests stay quick.
const char* const kQuickAuto = "[run]\nmin_runs = 8\nmax_runs = 256\nconvergence_tolerance = 0.1\n";

// A fresh folder `name` with a 400 x 300 m slope falling south at 8 m per 10 m cell that levels
// off from row 12 (the rocks come to rest), released from row 1, columns `first` to `last`.
fs::path fresh_scene(const std::string& name, int first, int last) {
  const fs::path folder = test::fresh_folder(name);
  test::RasterFixture dem;
  dem.value = [](int, int row) { return 1000.0 - 8.0 * std::min(row, 12); };
  write_raster(folder / "dem.tif", dem);
  test::RasterFixture release;
  release.value = [first, last](int col, int row) { return row == 1 && col >= first && col <= last ? 1.0 : 0.0; };
  write_raster(folder / "release.tif", release);
  return folder;
}

struct RockfallRun {
  test::ProgramResult result;
  nlohmann::json record;
};

// talus rockfall on the scene in `folder`, into folder / out, with these extra arguments and scenario.
RockfallRun run_scene(const fs::path& folder, const std::string& out, std::vector<std::string> extra,
              const std::string& scenario) {
  std::vector<std::string> arguments = {"rockfall", "--dem", (folder / "dem.tif").string(), "--release",
                                        (folder / "release.tif").string(), "--out", (folder / out).string()};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  if (!scenario.empty()) {
    std::ofstream(folder / (out + ".toml")) << scenario;
    arguments.insert(arguments.end(), {"--scenario", (folder / (out + ".toml")).string()});
  }
  RockfallRun run{test::run_talus(arguments, folder), {}};
  std::ifstream in(folder / out / "run.json");
  if (in) run.record = nlohmann::json::parse(in);
  return run;
}

void expect_same_layers(const fs::path& a, const fs::path& b) {
  for (const char* layer : kLayers) {
    const auto one = test::read_band(a / (std::string(layer) + ".tif"));
    const auto two = test::read_band(b / (std::string(layer) + ".tif"));
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(float)), 0) << layer << " differs";
  }
}

bool has_problem(const RockfallRun& run, const std::string& start) {
  return std::any_of(run.record["problems"].begin(), run.record["problems"].end(),
                     [&](const nlohmann::json& p) { return p.get<std::string>().rfind(start, 0) == 0; });
}

class AutoRuns : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = fresh_scene("rockfall_auto_runs", 5, 34);
    one_ = std::make_unique<RockfallRun>(run_scene(folder_, "t1", {"--runs", "auto", "--threads", "1"}, kQuickAuto));
    two_ = std::make_unique<RockfallRun>(run_scene(folder_, "t2", {"--runs", "auto", "--threads", "2"}, kQuickAuto));
  }
  static void TearDownTestSuite() {
    one_.reset();
    two_.reset();
    fs::remove_all(folder_);
  }
  static fs::path folder_;
  static std::unique_ptr<RockfallRun> one_, two_;
};
fs::path AutoRuns::folder_;
std::unique_ptr<RockfallRun> AutoRuns::one_, AutoRuns::two_;

TEST_F(AutoRuns, RecordsTheRunsOfEverySource) {
  ASSERT_EQ(two_->result.exit_code, 0) << two_->result.err;
  const nlohmann::json& runs = two_->record["runs"];
  EXPECT_EQ(runs["mode"], "auto");
  EXPECT_EQ(runs["limit"], 256);
  ASSERT_EQ(runs["per_source"].size(), 30u);
  std::uint64_t total = 0, counted = 0;
  for (const auto& n : runs["per_source"]) {
    const auto r = n.get<std::uint64_t>();
    EXPECT_TRUE(r >= 8 && r <= 256 && r % 8 == 0 && ((r / 8) & (r / 8 - 1)) == 0) << r;
    total += r;
  }
  for (const auto& [runs_text, sources] : runs["sources_by_runs"].items()) counted += sources.get<std::uint64_t>();
  EXPECT_EQ(counted, 30u);
  EXPECT_EQ(runs["total"], total);
  EXPECT_EQ(two_->record["counts"]["trajectories"], total);
  EXPECT_EQ(two_->record["parameters"]["run"]["runs"], "auto");
  EXPECT_NE(two_->result.out.find("Runs per source (--runs auto): "), std::string::npos) << two_->result.out;
  EXPECT_NE(two_->result.err.find("Progress: 100%"), std::string::npos);
}

TEST_F(AutoRuns, ConvergesWithinTheTolerance) {
  ASSERT_EQ(two_->result.exit_code, 0) << two_->result.err;
  const nlohmann::json& c = two_->record["convergence"];
  EXPECT_EQ(c["tolerance"], 0.1);
  EXPECT_EQ(c["sources"], 30);
  EXPECT_TRUE(c["converged"].get<bool>()) << c.dump();
  EXPECT_LT(c["reach_change"].get<double>(), 0.1);
  EXPECT_LT(c["energy_change"].get<double>(), 0.1);
  EXPECT_TRUE(c["runs_suggested"].is_null());
  EXPECT_FALSE(has_problem(*two_, "convergence: ")) << two_->record["problems"].dump();
  EXPECT_NE(two_->result.out.find(": converged ([run] convergence_tolerance = 10 %)"), std::string::npos)
      << two_->result.out;
}

TEST_F(AutoRuns, SameLayersAndRunsAtOneAndTwoThreads) {
  ASSERT_EQ(one_->result.exit_code, 0) << one_->result.err;
  ASSERT_EQ(two_->result.exit_code, 0) << two_->result.err;
  EXPECT_EQ(one_->record["runs"]["per_source"], two_->record["runs"]["per_source"]);
  EXPECT_EQ(one_->record["convergence"], two_->record["convergence"]);
  expect_same_layers(folder_ / "t1", folder_ / "t2");
}

TEST(AutoRunsOneSource, EndingAtNRunsGivesTheLayersOfRunsN) {
  const auto folder = fresh_scene("rockfall_auto_equals_fixed", 20, 20);
  const RockfallRun automatic = run_scene(folder, "auto", {"--threads", "2"}, kQuickAuto);
  ASSERT_EQ(automatic.result.exit_code, 0) << automatic.result.err;
  ASSERT_EQ(automatic.record["runs"]["per_source"].size(), 1u);
  const auto n = automatic.record["runs"]["per_source"][0].get<std::uint64_t>();
  const RockfallRun fixed = run_scene(folder, "fixed", {"--runs", std::to_string(n), "--threads", "1"}, "");
  ASSERT_EQ(fixed.result.exit_code, 0) << fixed.result.err;
  EXPECT_EQ(fixed.record["counts"]["trajectories"], n);
  expect_same_layers(folder / "auto", folder / "fixed");
  // The same runs, so the same test: fixed N compares N/2 with N as auto's last doubling did.
  EXPECT_EQ(automatic.record["convergence"]["reach_change"], fixed.record["convergence"]["reach_change"]);
  EXPECT_EQ(automatic.record["convergence"]["energy_change"], fixed.record["convergence"]["energy_change"]);
  fs::remove_all(folder);
}

TEST(FixedRuns, TooFewAreAProblemThatNamesTheRunsNeeded) {
  const auto folder = fresh_scene("rockfall_too_few_runs", 5, 34);
  const RockfallRun run = run_scene(folder, "out", {"--runs", "2", "--threads", "2"}, "");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  const nlohmann::json& c = run.record["convergence"];
  EXPECT_FALSE(c["converged"].get<bool>());
  EXPECT_EQ(c["tolerance"], 0.05);
  const auto suggested = c["runs_suggested"].get<std::uint64_t>();
  EXPECT_GT(suggested, 2u);
  EXPECT_EQ(run.record["runs"]["mode"], "fixed");
  EXPECT_FALSE(run.record["runs"].contains("per_source"));
  std::string line;
  for (const auto& p : run.record["problems"]) {
    if (p.get<std::string>().rfind("convergence: ", 0) == 0) line = p.get<std::string>();
  }
  ASSERT_FALSE(line.empty()) << run.record["problems"].dump();
  EXPECT_EQ(line.rfind("convergence: the maps have not converged with 2 runs per source: ", 0), 0u) << line;
  EXPECT_NE(line.find(" of 30 sources ("), std::string::npos) << line;
  EXPECT_NE(line.find(" reached cells ("), std::string::npos) << line;
  EXPECT_NE(line.find("use --runs " + std::to_string(suggested) + ", or --runs auto"), std::string::npos) << line;
  EXPECT_NE(run.result.out.find("problem: " + line + "\n"), std::string::npos) << run.result.out;
  fs::remove_all(folder);
}

// Issue 38, item 4: each intensity class counts its cells passed by fewer than 20 rocks (too few
// for a 95th percentile), as the layers show them, and a class with more than 10 % such cells is
// a problem line.
TEST(FixedRuns, IntensityCellsTooThinForTheirPercentileAreCountedAndAProblem) {
  const auto folder = fresh_scene("rockfall_thin_classes", 5, 34);
  const RockfallRun run = run_scene(folder, "out", {"--runs", "4", "--threads", "2"}, "");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  const auto intensity = test::read_band(folder / "out" / "intensity.tif");
  const auto passages = test::read_band(folder / "out" / "passages.tif");
  ASSERT_EQ(intensity.size(), passages.size());
  int problem_lines = 0;
  for (const auto& c : run.record["intensity"]["classes"]) {
    std::int64_t cells = 0, thin = 0;
    for (std::size_t k = 0; k < intensity.size(); ++k) {
      if (intensity[k] != c["value"].get<float>()) continue;
      ++cells;
      thin += passages[k] < 20.0f;
    }
    EXPECT_EQ(c["cells"], cells) << c.dump();
    EXPECT_EQ(c["cells_under_20_passages"], thin) << c.dump();
    if (cells > 0 && thin > cells / 10) {
      ++problem_lines;
      EXPECT_TRUE(has_problem(run, "intensity: " + std::to_string(thin) + " of the " + std::to_string(cells) + " " +
                                       c["name"].get<std::string>() + " cells ("))
          << run.record["problems"].dump();
    }
  }
  EXPECT_GT(problem_lines, 0) << "four runs per source leave thin classes";
  EXPECT_NE(run.result.out.find("problem: intensity: "), std::string::npos) << run.result.out;
  fs::remove_all(folder);
}

// Issue 38, item 4: with --runs auto, sources that stop unconverged at the run limit are a
// problem line even where the maps converged as a whole.
TEST(AutoRunsOneSource, SourcesStoppedAtTheLimitAreAProblemWhenTheWholeConverged) {
  const auto folder = fresh_scene("rockfall_auto_at_limit", 5, 34);
  const RockfallRun run =
      run_scene(folder, "out", {"--runs", "auto"}, "[run]\nmin_runs = 4\nmax_runs = 8\nconvergence_tolerance = 0.3\n");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  const nlohmann::json& c = run.record["convergence"];
  ASSERT_TRUE(c["converged"].get<bool>()) << c.dump();
  ASSERT_GT(c["sources_at_limit"].get<int>(), 0) << c.dump();
  EXPECT_TRUE(has_problem(run, "convergence: " + std::to_string(c["sources_at_limit"].get<int>()) +
                                   " of 30 sources (")) << run.record["problems"].dump();
  EXPECT_NE(run.result.out.find("stopped unconverged at the limit of 8 runs: the maps converged as a whole"),
            std::string::npos) << run.result.out;
  fs::remove_all(folder);
}

TEST(FixedRuns, OneRunPerSourceIsNotTested) {
  const auto folder = fresh_scene("rockfall_only_run_untested", 5, 34);
  const RockfallRun run = run_scene(folder, "out", {"--runs", "auto", "--only-run", "3"}, "");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  EXPECT_TRUE(run.record["convergence"].is_null());
  EXPECT_EQ(run.record["counts"]["trajectories"], 30);
  EXPECT_FALSE(has_problem(run, "convergence: "));
  fs::remove_all(folder);
}

struct BadRuns {
  std::string name;
  std::vector<std::string> arguments;
  std::string scenario;
  std::string message;  // a phrase of the error line
};
void PrintTo(const BadRuns& bad, std::ostream* os) { *os << bad.name; }

class BadRunSettings : public ::testing::TestWithParam<BadRuns> {};

TEST_P(BadRunSettings, ExitTwoWithOneLineAndWriteNothing) {
  const BadRuns& bad = GetParam();
  const auto folder = fresh_scene("rockfall_bad_runs_" + bad.name, 5, 6);
  const RockfallRun run = run_scene(folder, "out", bad.arguments, bad.scenario);
  EXPECT_EQ(run.result.exit_code, 2) << run.result.out;
  EXPECT_EQ(std::count(run.result.err.begin(), run.result.err.end(), '\n'), 1) << run.result.err;
  EXPECT_EQ(run.result.err.rfind("talus: error: ", 0), 0u) << run.result.err;
  EXPECT_NE(run.result.err.find(bad.message), std::string::npos) << run.result.err;
  EXPECT_FALSE(fs::exists(folder / "out"));
  fs::remove_all(folder);
}

INSTANTIATE_TEST_SUITE_P(
    Rockfall, BadRunSettings,
    ::testing::Values(
        BadRuns{"not_a_number", {"--runs", "abc"}, "", "--runs abc: expected a whole number or auto"},
        BadRuns{"negative", {"--runs", "-3"}, "", "--runs -3: expected a whole number or auto"},
        BadRuns{"zero", {"--runs", "0"}, "", "--runs 0: at least one run per source"},
        BadRuns{"max_below_first_batch", {"--runs", "auto"}, "[run]\nmin_runs = 40\nmax_runs = 30\n",
                "[run] max_runs 30: below [run] min_runs 40, the first batch of --runs auto"},
        BadRuns{"min_below_two", {}, "[run]\nmin_runs = 1\n", "[run] min_runs 1: --runs auto needs at least 2"},
        BadRuns{"tolerance_not_a_fraction", {"--runs", "10"}, "[run]\nconvergence_tolerance = 1.5\n",
                "[run] convergence_tolerance 1.500000: expected a fraction between 0 and 1"},
        BadRuns{"scenario_word", {}, "[run]\nruns = \"sometimes\"\n", "[run] runs sometimes: expected a whole number or auto"},
        BadRuns{"scenario_type", {}, "[run]\nruns = 2.5\n", "[run] runs must be a whole number or \"auto\""},
        BadRuns{"only_run_beyond_the_limit", {"--runs", "auto", "--only-run", "256"}, kQuickAuto,
                "--only-run 256: runs are numbered 0 to the auto limit - 1 (255)"}));

TEST(ScenarioRuns, AutoAndAWholeNumberAreTakenFromTheScenario) {
  const auto folder = fresh_scene("rockfall_scenario_runs", 5, 6);
  const RockfallRun automatic = run_scene(folder, "auto", {}, std::string("[run]\nruns = \"auto\"\nmin_runs = 8\nmax_runs = 64\n"));
  ASSERT_EQ(automatic.result.exit_code, 0) << automatic.result.err;
  EXPECT_EQ(automatic.record["runs"]["mode"], "auto");
  EXPECT_EQ(automatic.record["runs"]["limit"], 64);
  const RockfallRun three = run_scene(folder, "three", {}, "[run]\nruns = 3\n");
  ASSERT_EQ(three.result.exit_code, 0) << three.result.err;
  EXPECT_EQ(three.record["runs"]["mode"], "fixed");
  EXPECT_EQ(three.record["counts"]["trajectories"], 6);
  EXPECT_EQ(three.record["parameters"]["run"]["runs"], 3);
  // The flag overrides the scenario.
  const RockfallRun flag = run_scene(folder, "flag", {"--runs", "2"}, "[run]\nruns = \"auto\"\n");
  ASSERT_EQ(flag.result.exit_code, 0) << flag.result.err;
  EXPECT_EQ(flag.record["counts"]["trajectories"], 4);
  fs::remove_all(folder);
}

}  // namespace
}  // namespace talus
