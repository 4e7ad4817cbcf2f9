// The bad-input table of issue 18, item 6: each kind of bad input that once got through, with
// cases of its own, refused by `talus rockfall` or `talus mudflow` with exit code 2, one line
// `talus: error: WHERE: PROBLEM` naming the file (and its role) or the option, and nothing
// written. The kinds: inputs that hung a run, that gave a silently wrong map, that ended in exit
// code 1 or a crash, that were found only after the work, that left files behind, and that were
// misreported. `talus info`'s refusals of files, a DEM header of 320 GB among them, are in
// bad_input_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <map>

#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

// What the output folder is before the run: absent, a complete Talus set of an earlier run, or
// a folder of someone else's files. The run must leave it as it was.
enum class Before { absent, talus_set, foreign_folder };

struct BadRun {
  std::string kind;                    // hang, wrong_map, exit_1, too_late, left_behind, misreported
  std::string name;                    // test name
  std::vector<std::string> arguments;  // @IN/: the inputs folder, @SAMPLE/: sample_dem, @OUT: the output folder
  std::string where;                   // the file and role, or the option, that the line names
  std::string problem;                 // a phrase of the line
  Before before = Before::absent;
};

void PrintTo(const BadRun& bad, std::ostream* os) { *os << bad.kind << "/" << bad.name; }

// `arguments` with each option of `extra` set: an option already there gets the new value, any
// other is added with the values after it.
std::vector<std::string> with_options(std::vector<std::string> arguments, const std::vector<std::string>& extra) {
  for (std::size_t k = 0; k < extra.size(); ++k) {
    const bool has_value = k + 1 < extra.size() && extra[k + 1].rfind("--", 0) != 0;
    const auto given = std::find(arguments.begin(), arguments.end(), extra[k]);
    if (given != arguments.end() && has_value) {
      *(given + 1) = extra[++k];
    } else {
      arguments.push_back(extra[k]);
      if (has_value) arguments.push_back(extra[++k]);
    }
  }
  return arguments;
}

// The sample scene's rock fall with 1 run per source, or its mud flow for 1 s, with `extra`.
std::vector<std::string> rockfall(const std::vector<std::string>& extra) {
  return with_options({"rockfall", "--dem", "@SAMPLE/dem.tif", "--release", "@SAMPLE/rockfall_release.gpkg", "--out",
                       "@OUT", "--runs", "1"},
                      extra);
}
std::vector<std::string> mudflow(const std::vector<std::string>& extra) {
  return with_options({"mudflow", "--dem", "@SAMPLE/dem.tif", "--release", "@SAMPLE/mudflow_release.gpkg", "--out",
                       "@OUT", "--duration", "1"},
                      extra);
}
// The same, with a release or DEM of the inputs folder in place of the sample's.
std::vector<std::string> with_input(std::vector<std::string> arguments, const std::string& option, const std::string& file) {
  *(std::find(arguments.begin(), arguments.end(), option) + 1) = "@IN/" + file;
  return arguments;
}

// Scenario and materials files, one bad value each, by file name.
const std::map<std::string, std::string> kTextFiles = {
    {"contact_time_step_0.toml", "[fast_bounce]\ncontact_time_step = 0\n"},
    {"contact_speed_nan.toml", "[fast_bounce]\ncontact_speed = nan\n"},
    {"noise_octaves_2e9.toml", "[stochastic]\nnoise_octaves = 2000000000\n"},
    {"map_interval_tiny.toml", "[outputs]\nmap_interval = 1e-300\n"},
    {"longest_step_tiny.toml", "[time_steps]\nlongest_step = 1e-300\n"},
    {"max_step_length_tiny.toml", "[fast_bounce]\nmax_step_length = 1e-9\n"},
    {"max_step_length_0.toml", "[fast_bounce]\nmax_step_length = 0\n"},
    {"gravity_negative.toml", "[fast_bounce]\ngravity = -9.81\n"},
    {"size_variation_2_5.toml", "[stochastic]\nsize_variation = 2.5\n"},
    {"mass_resolution_0.toml", "[full]\nmass_resolution = 0\n"},
    {"threads_wrapping.toml", "[run]\nthreads = 4294967297\n"},
    {"rock_density_50.toml", "[rock]\ndensity = 50.0\n"},
    {"materials_huge_friction.toml",
     "default_lithology = 4\ndefault_vegetation = 0\n\n[[lithology]]\ncode = 4\nname = \"talus\"\n"
     "elastic_slope = 1.0e8\nyield_pressure = 8.0e5\nplastic_slope = 7.0e7\nunloading_slope = 1.9e8\n"
     "friction = 1.0e6\nrolling_friction = 0.4\nrestitution_normal = 0.38\nrestitution_tangential = 0.65\n"
     "noise_amplitude = 0.3\n\n[[vegetation]]\ncode = 0\nname = \"bare\"\ndeperdition = 0.0\n"},
    {"plain.txt", "a file, not a folder\n"},
};

class BadRuns : public ::testing::TestWithParam<BadRun> {
 protected:
  static void SetUpTestSuite() {
    inputs_ = test::fresh_folder("bad_runs_inputs");
    for (const auto& [name, text] : kTextFiles) std::ofstream(inputs_ / name) << text;
    // The sample scene's CRS and grid: EPSG:31287, 5 m cells from (255302.0828, 380605.9942).
    // A release point 2^32 + 100 cells east of the corner, once taken as column 100.
    const std::string crs = "EPSG:31287";
    test::write_vector(inputs_ / "release_wrapping.gpkg", crs, {{"POINT(21475092284.58 380000)", 0}}, false);
    const std::string polygon = "POLYGON((255630 380300,255660 380300,255660 380270,255630 380270,255630 380300))";
    test::write_vector(inputs_ / "depth_nan.gpkg", crs, {{polygon, std::numeric_limits<double>::quiet_NaN()}}, true);
    test::write_vector(inputs_ / "depth_inf.gpkg", crs, {{polygon, std::numeric_limits<double>::infinity()}}, true);
    test::RasterFixture tiny_cells;
    tiny_cells.cell = 1e-142;
    write_raster(inputs_ / "dem_tiny_cells.tif", tiny_cells);
    // A complete set of an earlier run, copied in front of the cases that must leave one alone.
    earlier_set_ = inputs_ / "earlier_set";
    const auto sample = test::source_dir() / "sample_dem";
    const auto earlier = test::run_talus({"rockfall", "--dem", (sample / "dem.tif").string(), "--release",
                                          (sample / "rockfall_release.gpkg").string(), "--out", earlier_set_.string(),
                                          "--runs", "1"},
                                         inputs_);
    ASSERT_EQ(earlier.exit_code, 0) << earlier.err;
  }
  static void TearDownTestSuite() { fs::remove_all(inputs_); }
  static fs::path inputs_, earlier_set_;
};
fs::path BadRuns::inputs_, BadRuns::earlier_set_;

// Every file under `folder` with its bytes, to tell that a run left it as it was.
std::map<std::string, std::string> contents(const fs::path& folder) {
  std::map<std::string, std::string> files;
  if (!fs::exists(folder)) return files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    files[fs::relative(entry.path(), folder).string()] = std::string(std::istreambuf_iterator<char>(in), {});
  }
  return files;
}

TEST_P(BadRuns, ExitTwoWithOneLineNamingTheInputAndLeaveTheOutputAsItWas) {
  const BadRun& bad = GetParam();
  const auto work = test::fresh_folder("bad_run_" + bad.kind + "_" + bad.name);
  const auto out = work / "out";
  if (bad.before == Before::talus_set) fs::copy(earlier_set_, out, fs::copy_options::recursive);
  if (bad.before == Before::foreign_folder) {
    fs::create_directories(out / "notes");
    std::ofstream(out / "notes" / "field_book.txt") << "measured 2026-06-01\n";
  }
  const auto before = contents(out);
  std::vector<std::string> arguments;
  for (std::string a : bad.arguments) {
    if (a.rfind("@IN/", 0) == 0) a = (inputs_ / a.substr(4)).string();
    if (a.rfind("@SAMPLE/", 0) == 0) a = (test::source_dir() / "sample_dem" / a.substr(8)).string();
    if (a.rfind("@OUT", 0) == 0) a = out.string() + a.substr(4);
    arguments.push_back(a);
  }
  const auto result = test::run_talus(arguments, work);
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(result.err.rfind("talus: error: ", 0), 0u) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_NE(result.err.find(bad.where), std::string::npos) << result.err;
  EXPECT_NE(result.err.find(bad.problem), std::string::npos) << result.err;
  EXPECT_EQ(result.out.find("Progress"), std::string::npos) << "refused only after work:\n" << result.out;
  EXPECT_EQ(contents(out), before) << "the output folder changed";
  EXPECT_EQ(fs::exists(out), bad.before != Before::absent);
  std::string left;  // no staging folder or other file beside the output folder
  for (const auto& entry : fs::directory_iterator(work)) {
    if (entry.path() != out) left += entry.path().filename().string() + " ";
  }
  EXPECT_EQ(left, "") << "left in the working folder";
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, BadRuns,
    ::testing::Values(
        // Once never finished.
        BadRun{"hang", "contact_time_step_0", rockfall({"--scenario", "@IN/contact_time_step_0.toml"}),
               "contact_time_step_0.toml (scenario): [fast_bounce] contact_time_step", "expected 0.0001-10 s"},
        BadRun{"hang", "contact_speed_nan", rockfall({"--scenario", "@IN/contact_speed_nan.toml"}),
               "contact_speed_nan.toml (scenario): [fast_bounce] contact_speed nan", "expected 0.001-100 m/s"},
        BadRun{"hang", "noise_octaves_2e9", rockfall({"--scenario", "@IN/noise_octaves_2e9.toml"}),
               "noise_octaves_2e9.toml (scenario): [stochastic] noise_octaves 2000000000", "expected 0-16"},
        BadRun{"hang", "mud_map_interval_tiny", mudflow({"--scenario", "@IN/map_interval_tiny.toml"}),
               "map_interval_tiny.toml (scenario): [outputs] map_interval 1e-300", "expected 0.01-3600 s"},
        BadRun{"hang", "max_step_length_tiny", rockfall({"--scenario", "@IN/max_step_length_tiny.toml"}),
               "max_step_length_tiny.toml (scenario): [fast_bounce] max_step_length 1e-09", "expected 0.001-100 m"},
        BadRun{"hang", "mud_longest_step_tiny", mudflow({"--scenario", "@IN/longest_step_tiny.toml"}),
               "longest_step_tiny.toml (scenario): [time_steps] longest_step 1e-300", "expected 0.001-10 s"},
        // Once gave all-zero, negative or misplaced layers with exit code 0.
        BadRun{"wrong_map", "release_wrapping_column", with_input(rockfall({}), "--release", "release_wrapping.gpkg"),
               "release_wrapping.gpkg (release)", "outside the DEM"},
        BadRun{"wrong_map", "max_step_length_0", rockfall({"--scenario", "@IN/max_step_length_0.toml"}),
               "(scenario): [fast_bounce] max_step_length 0", "expected 0.001-100 m"},
        BadRun{"wrong_map", "gravity_negative", rockfall({"--scenario", "@IN/gravity_negative.toml"}),
               "(scenario): [fast_bounce] gravity -9.81", "expected 0.1-100 m/s2"},
        BadRun{"wrong_map", "size_variation_2_5", rockfall({"--scenario", "@IN/size_variation_2_5.toml"}),
               "(scenario): [stochastic] size_variation 2.5", "expected 0-0.9"},
        BadRun{"wrong_map", "mud_depth_nan", with_input(mudflow({}), "--release", "depth_nan.gpkg"),
               "depth_nan.gpkg (release)", "has no release depth"},
        BadRun{"wrong_map", "dem_tiny_cells", with_input(rockfall({}), "--dem", "dem_tiny_cells.tif"),
               "dem_tiny_cells.tif (DEM)", "expected 0.01-10000 m"},
        BadRun{"wrong_map", "mud_particle_size_huge", mudflow({"--particle-size", "1e9"}), "--particle-size 1000000000",
               "expected 0.05-100 m"},
        // Once ended in exit code 1 or a crash.
        BadRun{"exit_1", "runs_1e12", rockfall({"--runs", "1000000000000"}), "--runs 1000000000000",
               "expected 1-1000000000 runs"},
        BadRun{"exit_1", "runs_negative", rockfall({"--runs", "-1"}), "--runs -1", "expected a whole number or auto"},
        BadRun{"exit_1", "mass_resolution_0", rockfall({"--mode", "full", "--scenario", "@IN/mass_resolution_0.toml"}),
               "(scenario): [full] mass_resolution 0", "expected 1-1000"},
        BadRun{"exit_1", "threads_ten_million", rockfall({"--threads", "10000000"}), "--threads 10000000",
               "expected 0 (all cores) or 1-1024"},
        // Once found only after the whole simulation.
        BadRun{"too_late", "out_under_a_file", rockfall({"--out", "@IN/plain.txt/out"}), "plain.txt/out (--out)",
               "Not a directory"},
        BadRun{"too_late", "out_in_proc", mudflow({"--out", "/proc/talus_out"}), "/proc/talus_out (--out)",
               "cannot write into /proc"},
        BadRun{"too_late", "snapshots_tiny", mudflow({"--snapshots", "1e-6"}), "--snapshots 1e-06",
               "expected 0 (none) or 0.01-86400 s"},
        BadRun{"too_late", "snapshots_too_many", mudflow({"--snapshots", "0.01", "--duration", "5000"}),
               "--snapshots 0.01", "at most 100000 snapshots"},
        // Once left files of its own, or of an earlier run, behind.
        BadRun{"left_behind", "foreign_folder", rockfall({}), "(--out)", "not a Talus layer set",
               Before::foreign_folder},
        BadRun{"left_behind", "failed_over_earlier_set", rockfall({"--scenario", "@IN/gravity_negative.toml"}),
               "gravity_negative.toml (scenario)", "expected 0.1-100 m/s2", Before::talus_set},
        BadRun{"left_behind", "failed_mud_over_earlier_set", with_input(mudflow({}), "--release", "depth_inf.gpkg"),
               "depth_inf.gpkg (release)", "of inf m", Before::talus_set},
        BadRun{"left_behind", "failed_into_new_nested_folder", with_input(rockfall({"--out", "@OUT/a/b"}), "--dem",
                                                                          "dem_tiny_cells.tif"),
               "dem_tiny_cells.tif (DEM)", "expected 0.01-10000 m"},
        // Once named the wrong thing, or wrapped a number around.
        BadRun{"misreported", "seed_negative", rockfall({"--seed", "-1"}), "--seed",
               "expected a whole number from 0 to 18446744073709551615, got -1"},
        BadRun{"misreported", "mud_seed_2_64", mudflow({"--seed", "18446744073709551616"}), "--seed",
               "got 18446744073709551616"},
        BadRun{"misreported", "mud_threads_wrapping", mudflow({"--scenario", "@IN/threads_wrapping.toml"}),
               "threads_wrapping.toml (scenario): [run] threads", "at most 2147483647"},
        BadRun{"misreported", "rock_threads_negative", rockfall({"--threads", "-1"}), "--threads -1",
               "expected 0 (all cores) or 1-1024"},
        BadRun{"misreported", "materials_role", rockfall({"--materials", "@IN/materials_huge_friction.toml"}),
               "materials_huge_friction.toml (materials): 'friction' in lithology class 4 = 1.0e6",
               "expected 0.0 to 10.0"},
        BadRun{"misreported", "mud_depth_inf", with_input(mudflow({}), "--release", "depth_inf.gpkg"),
               "depth_inf.gpkg (release)", "of inf m"},
        BadRun{"misreported", "rock_density_from_scenario", rockfall({"--scenario", "@IN/rock_density_50.toml"}),
               "rock_density_50.toml (scenario): [rock] density 50", "expected 500-6000 kg/m3"}),
    [](const ::testing::TestParamInfo<BadRun>& case_info) { return case_info.param.kind + "_" + case_info.param.name; });

}  // namespace
}  // namespace talus
