// `talus study` (issue 19, items 1-2; docs/study.md): every scenario of a study file runs as its
// subcommand would, into its own folder, with layers bit-identical to the subcommand's own run;
// study.json records each scenario; a bad study file or a bad input of any scenario is refused
// with one line, exit code 2 and nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "layer_contract.hpp"
#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "talus/gis/build_commit.hpp"
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

// `talus study STUDY --out resumed` in `folder`, killed with SIGKILL after `seconds` (if still running).
void study_until_killed(const fs::path& folder, const fs::path& study, double seconds) {
  const std::string command = "cd '" + folder.string() + "' && timeout -s KILL " + std::to_string(seconds) + " '" +
                              test::talus_exe().string() + "' study '" + study.string() +
                              "' --out resumed --project off >/dev/null 2>&1";
  std::system(command.c_str());
}

fs::path write_study(const fs::path& folder, const std::string& text) {
  const fs::path file = folder / "study.toml";
  std::ofstream(file) << text;
  return file;
}

std::string replaced(std::string text, const std::string& what, const std::string& by) {
  const auto at = text.find(what);
  return at == std::string::npos ? text : text.replace(at, what.size(), by);
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
  EXPECT_EQ(test::layer_contract_problems("rockfall", folder / "out/scenarios/blocks", sample / "dem.tif"),
            test::kNoProblems);
  EXPECT_EQ(test::layer_contract_problems("mudflow", folder / "out/scenarios/mud", sample / "dem.tif"),
            test::kNoProblems);

  std::ifstream record_file(folder / "out/study.json");
  const nlohmann::json record = nlohmann::json::parse(record_file);
  EXPECT_EQ(record["talus_version"], TALUS_VERSION);
  EXPECT_EQ(record["git_commit"], std::string(gis::git_commit()));
  ASSERT_EQ(record["scenarios"].size(), 2u);
  EXPECT_EQ(record["scenarios"][0]["name"], "blocks");
  EXPECT_EQ(record["scenarios"][0]["process"], "rockfall");
  EXPECT_DOUBLE_EQ(record["scenarios"][0]["return_period_years"].get<double>(), 30.0);
  EXPECT_EQ(record["scenarios"][0]["parameters"]["run"]["seed"], 7);
  EXPECT_EQ(record["scenarios"][0]["counts"]["trajectories"], 3 * 260);
  EXPECT_DOUBLE_EQ(record["scenarios"][1]["return_period_years"].get<double>(), 100.0);
  EXPECT_EQ(record["scenarios"][1]["folder"], "scenarios/mud");
  EXPECT_EQ(record["hazard"]["guideline"], "foen-2016");
}

// The published Swiss matrix (FOEN 2016 after BRP/BWW/BUWAL 1997), written out here apart from
// src/cli/intensity_guidelines.toml: degree 4 high, 3 medium, 2 low, 1 residual, per intensity
// class 1 weak, 2 medium, 3 strong and per probability class of the return period.
float swiss_degree(float intensity, double return_period) {
  const int column = return_period <= 30 ? 0 : return_period <= 100 ? 1 : return_period <= 300 ? 2 : 3;
  static const float kDegrees[3][4] = {{3, 2, 2, 1}, {4, 3, 3, 1}, {4, 4, 4, 1}};
  return intensity >= 1 ? kDegrees[static_cast<int>(intensity) - 1][column] : 0.0f;
}

// issue 19, item 3: hazard.tif holds, per cell, the highest degree of the scenarios' intensity at
// their return periods; each process's map its own scenarios'; both open styled in QGIS, and the
// zones as polygons with a categorized style.
TEST(Study, TheHazardMapTakesEachCellsHighestDegreeOverTheScenarios) {
  const fs::path folder = test::fresh_folder("study_hazard");
  std::string text = sample_study();
  // A second, rarer rock fall of bigger blocks, so that a cell's degree comes from several scenarios.
  const fs::path sample = test::source_dir() / "sample_dem";
  text += "[[rockfall]]\nname = \"big\"\nrelease = \"" + (sample / "rockfall_release.gpkg").string() +
          "\"\nreturn_period = 1000\n[rockfall.run]\nruns = 3\n[rockfall.rock]\nsize = \"3\"\n"
          "[rockfall.outputs]\nproject = \"off\"\n";
  const fs::path study = write_study(folder, text);
  const test::ProgramResult run = test::run_talus({"study", study.string(), "--out", "out"}, folder);
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;

  const struct {
    const char* name;
    double return_period;
    bool rockfall;
  } scenarios[] = {{"blocks", 30, true}, {"big", 1000, true}, {"mud", 100, false}};
  const std::size_t cells = band(folder / "out/hazard/hazard.tif").size();
  std::vector<float> both(cells, 0.0f), rockfall(cells, 0.0f), mudflow(cells, 0.0f);
  for (const auto& s : scenarios) {
    const std::vector<float> intensity = band(folder / "out/scenarios" / s.name / "intensity.tif");
    // A rock fall reaches a cell once in 1 / reach_probability of its events (the default
    // [hazard] rockfall_probability = "reach").
    const std::vector<float> reach =
        s.rockfall ? band(folder / "out/scenarios" / s.name / "reach_probability.tif") : std::vector<float>(cells, 1.0f);
    for (std::size_t cell = 0; cell < cells; ++cell) {
      if (intensity[cell] < 0) {
        both[cell] = rockfall[cell] = mudflow[cell] = intensity[cell];
        continue;
      }
      if (!(reach[cell] > 0.0f)) continue;
      const float degree = swiss_degree(intensity[cell], s.return_period / std::min(1.0, double(reach[cell])));
      (s.rockfall ? rockfall : mudflow)[cell] = std::max((s.rockfall ? rockfall : mudflow)[cell], degree);
      both[cell] = std::max(both[cell], degree);
    }
  }
  EXPECT_EQ(band(folder / "out/hazard/hazard.tif"), both);
  EXPECT_EQ(band(folder / "out/hazard/hazard_rockfall.tif"), rockfall);
  EXPECT_EQ(band(folder / "out/hazard/hazard_mudflow.tif"), mudflow);
  for (const float degree : {1.0f, 2.0f, 3.0f, 4.0f}) {  // every degree occurs
    EXPECT_GT(std::count(both.begin(), both.end(), degree), 0) << degree;
  }

  const std::string qgis = "/usr/bin/python3 " + (test::source_dir() / "tests/gis/qgis").string();
  const std::string hazard = (folder / "out/hazard").string();
  EXPECT_EQ(std::system((qgis + "/check_layer_in_qgis.py EPSG:31287 " + hazard +
                         "/hazard.tif 'Hazard degree (foen-2016; rock fall per cell: return period / reach probability)' " + hazard +
                         "/hazard_mudflow.tif 'Hazard degree, mud flow (foen-2016)'").c_str()),
            0);
  EXPECT_EQ(std::system((qgis + "/check_zones_in_qgis.py EPSG:31287 " + hazard + "/hazard_zones.gpkg 400").c_str()), 0);

  // issue 19, item 2: the region's layers are the envelope of each process's scenarios.
  for (const char* name : {"energy_max", "reach_probability", "intensity"}) {
    std::vector<float> largest = band(folder / "out/scenarios/blocks" / (std::string(name) + ".tif"));
    const std::vector<float> big = band(folder / "out/scenarios/big" / (std::string(name) + ".tif"));
    for (std::size_t cell = 0; cell < cells; ++cell) largest[cell] = std::max(largest[cell], big[cell]);
    EXPECT_EQ(band(folder / "out/region/rockfall" / (std::string(name) + ".tif")), largest) << name;
    EXPECT_NE(largest, big) << name;  // both scenarios shape the envelope
  }
  EXPECT_EQ(band(folder / "out/region/mudflow/arrival_time.tif"), band(folder / "out/scenarios/mud/arrival_time.tif"));

  std::ifstream record_file(folder / "out/study.json");
  const nlohmann::json record = nlohmann::json::parse(record_file);
  EXPECT_EQ(record["region"]["rockfall"]["scenarios"], nlohmann::json({"blocks", "big"}));
  EXPECT_EQ(record["region"]["mudflow"]["layers"].size(), 6u);
  const auto& high = record["hazard"]["maps"]["hazard"][0];
  EXPECT_EQ(high["name"], "high");
  EXPECT_EQ(high["cells"], std::count(both.begin(), both.end(), 4.0f));
}

// issue 19, item 7: with --project on, project.qgz holds the hazard map and a group per scenario
// over the hillshade, quicklook/hazard.png shows the map, and report.md tabulates the study.
TEST(Study, TheSummaryHasAProjectAQuicklookAndAReport) {
  const fs::path folder = test::fresh_folder("study_summary");
  const fs::path study = write_study(folder, sample_study());
  const test::ProgramResult run = test::run_talus({"study", study.string(), "--out", "out", "--project", "on"}, folder);
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_EQ(std::system(("/usr/bin/python3 " + (test::source_dir() / "tests/gis/qgis/check_run_project.py").string() +
                         " " + (folder / "out").string() + " study hazard").c_str()),
            0);
  std::ifstream report_file(folder / "out/report.md");
  const std::string report((std::istreambuf_iterator<char>(report_file)), std::istreambuf_iterator<char>());
  for (const char* needed : {"# Hazard study: study.toml", "![Hazard map](quicklook/hazard.png)", "| high |",
                             "| blocks | rockfall | 30 |", "| mud | mudflow | 100 |", "## Problems"}) {
    EXPECT_NE(report.find(needed), std::string::npos) << needed << "\n" << report;
  }
}

// issue 19, item 5: a study killed (SIGKILL) at random moments and run again to the end gives the
// layers of an uninterrupted run, bit for bit, and a finished study run again computes nothing.
TEST(Study, AStudyKilledAtRandomMomentsResumesToTheSameLayers) {
  const fs::path folder = test::fresh_folder("study_resume");
  const std::string text = replaced(sample_study(), "runs = 3", "runs = 60");
  const fs::path study = write_study(folder, text);
  ASSERT_EQ(test::run_talus({"study", study.string(), "--out", "whole"}, folder).exit_code, 0);

  const auto run_until_killed = [&](double seconds) { study_until_killed(folder, study, seconds); };
  std::mt19937 random(19);  // fixed: the same kill moments on every run of the test
  std::uniform_real_distribution<double> moment(0.05, 1.5);  // s: within the first scenario (about 2 s)
  run_until_killed(moment(random));
  run_until_killed(moment(random));
  // Kills later and later, until the first scenario was committed before one of them.
  for (double seconds = 1.0; seconds < 20.0 && !fs::exists(folder / "resumed/.units/blocks.json"); seconds += 0.7) {
    run_until_killed(seconds);
  }
  ASSERT_TRUE(fs::exists(folder / "resumed/.units/blocks.json"));
  run_until_killed(moment(random));
  const test::ProgramResult last = test::run_talus({"study", study.string(), "--out", "resumed"}, folder);
  ASSERT_EQ(last.exit_code, 0) << last.out << last.err;
  EXPECT_NE(last.out.find("already done"), std::string::npos) << last.out;  // the committed scenario is kept
  for (const char* layer : {"scenarios/blocks/reach_probability.tif", "scenarios/blocks/energy_p95.tif",
                            "scenarios/blocks/passages.tif", "scenarios/mud/flow_depth_max.tif",
                            "scenarios/mud/deposit_depth.tif", "hazard/hazard.tif"}) {
    EXPECT_EQ(band(folder / "resumed" / layer), band(folder / "whole" / layer)) << layer;
  }
  const test::ProgramResult again = test::run_talus({"study", study.string(), "--out", "resumed"}, folder);
  ASSERT_EQ(again.exit_code, 0);
  EXPECT_EQ(again.out.find("trajectories in"), std::string::npos) << again.out;
  EXPECT_NE(again.out.find("already done"), std::string::npos) << again.out;
}

// issue 19, items 4 and 5: a rock fall in tiles commits each tile's units of work as they finish;
// killed at random moments within the scenario and run again, it takes the committed units as
// they are, computes the rest, and gives the layers of an uninterrupted run, bit for bit; the
// finished scenario keeps no units.
TEST(Study, ARockFallKilledWithinItsTilesResumesFromItsCommittedUnitsToTheSameLayers) {
  const fs::path folder = test::fresh_folder("study_resume_units");
  const fs::path sample = test::source_dir() / "sample_dem";
  const fs::path study = write_study(
      folder, "[inputs]\ndem = \"" + (sample / "dem.tif").string() + "\"\nlithology = \"" +
                  (sample / "lithology.tif").string() + "\"\n[[rockfall]]\nname = \"blocks\"\nrelease = \"" +
                  (sample / "rockfall_release.gpkg").string() +
                  "\"\nreturn_period = 30\n[rockfall.run]\nruns = 60\nseed = 7\n"
                  "[rockfall.tiles]\nsize = 30\nhalo = 1500\n[rockfall.outputs]\nproject = \"off\"\n");
  ASSERT_EQ(test::run_talus({"study", study.string(), "--out", "whole", "--project", "off"}, folder).exit_code, 0);

  const fs::path parts = folder / "resumed/.units/blocks.parts";
  const auto committed_units = [&] {
    std::size_t units = 0;
    if (fs::exists(parts)) {
      for (const auto& entry : fs::directory_iterator(parts)) units += entry.path().extension() == ".bin" ? 1 : 0;
    }
    return units;
  };
  const auto run_until_killed = [&](double seconds) { study_until_killed(folder, study, seconds); };
  std::mt19937 random(23);  // fixed: the same kill moments on every run of the test
  std::uniform_real_distribution<double> moment(0.05, 1.0);
  run_until_killed(moment(random));
  run_until_killed(moment(random));
  // Kills later and later, until one came after some units were committed.
  for (double seconds = 0.5; seconds < 20.0 && committed_units() == 0; seconds += 0.3) run_until_killed(seconds);
  ASSERT_GT(committed_units(), 0u);
  ASSERT_FALSE(fs::exists(folder / "resumed/.units/blocks.json"));
  const test::ProgramResult last = test::run_talus({"study", study.string(), "--out", "resumed", "--project", "off"}, folder);
  ASSERT_EQ(last.exit_code, 0) << last.out << last.err;
  EXPECT_NE(last.out.find("resumed: "), std::string::npos) << last.out;
  for (const char* layer : {"scenarios/blocks/reach_probability.tif", "scenarios/blocks/energy_p95.tif",
                            "scenarios/blocks/passages.tif", "scenarios/blocks/source_count.tif", "hazard/hazard.tif"}) {
    EXPECT_EQ(band(folder / "resumed" / layer), band(folder / "whole" / layer)) << layer;
  }
  EXPECT_FALSE(fs::exists(parts));
}

// issue 19, item 1: release = "auto" finds the sources from the slope. On the sample scene,
// lithology class 6 (bedrock) was made as the cells of Horn's slope >= 45 degrees
// (sample_dem/README.md), so sources steeper than 45 degrees in class 6 are those cells; without
// source_slope the DEM's own cliff threshold (Loye et al. 2009) applies.
TEST(Study, AutomaticSourcesComeFromTheSlope) {
  const fs::path folder = test::fresh_folder("study_sources");
  const fs::path sample = test::source_dir() / "sample_dem";
  const std::string inputs = "[inputs]\ndem = \"" + (sample / "dem.tif").string() + "\"\nlithology = \"" +
                             (sample / "lithology.tif").string() + "\"\n";
  const std::string scenario_tail = "return_period = 30\n[rockfall.run]\nruns = 2\n[rockfall.outputs]\nproject = \"off\"\n";
  const fs::path study = write_study(folder, inputs +
                                                 "[[rockfall]]\nname = \"bedrock\"\nrelease = \"auto\"\nsource_slope = 45\n"
                                                 "source_lithology = [6]\n" + scenario_tail +
                                                 "[[rockfall]]\nname = \"cliffs\"\nrelease = \"auto\"\n" + scenario_tail);
  const test::ProgramResult run = test::run_talus({"study", study.string(), "--out", "out"}, folder);
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;

  const std::vector<float> lithology = band(sample / "lithology.tif");
  const std::vector<float> bedrock = band(folder / "out/sources/bedrock.tif");
  std::size_t both = 0, lithology_only = 0, mask_only = 0;
  for (std::size_t cell = 0; cell < bedrock.size(); ++cell) {
    const bool rock = lithology[cell] == 6, source = bedrock[cell] == 1;
    both += rock && source;
    lithology_only += rock && !source;
    mask_only += source && !rock;
  }
  EXPECT_EQ(mask_only, 0u);
  EXPECT_GT(both, 2000u);
  EXPECT_LT(lithology_only, both / 100 + 10) << "the DEM's edge cells have no slope, the rest agree";

  std::ifstream record_file(folder / "out/study.json");
  const nlohmann::json record = nlohmann::json::parse(record_file);
  EXPECT_EQ(record["sources"]["bedrock"]["cells"], both);
  const double threshold = record["sources"]["cliffs"]["threshold_deg"].get<double>();
  EXPECT_GT(threshold, 50.0);  // the sample's cliff band: median slope 54 degrees
  EXPECT_LT(threshold, 65.0);
  const std::vector<float> cliffs = band(folder / "out/sources/cliffs.tif");
  const auto cliff_cells = std::count(cliffs.begin(), cliffs.end(), 1.0f);
  EXPECT_EQ(record["sources"]["cliffs"]["cells"], cliff_cells);
  EXPECT_EQ(record["scenarios"][1]["counts"]["sources"], cliff_cells);
  EXPECT_EQ(std::system(("/usr/bin/python3 " + (test::source_dir() / "tests/gis/qgis/check_layer_in_qgis.py").string() +
                         " EPSG:31287 " + (folder / "out/sources/cliffs.tif").string() +
                         " 'Potential rock-fall sources of cliffs'").c_str()),
            0);
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
      {"[hazard]\nrockfall_probability = \"max\"\n" + sample_study(), "use reach or onset"},
      {sample_study("source_slope = 50\n"), "are for release = \"auto\""},
      {replaced(sample_study("source_slope = 95\n"), (test::source_dir() / "sample_dem/rockfall_release.gpkg").string(),
                "auto"),
       "'source_slope' must be an angle of 1 to 89 degrees"},
      {replaced(sample_study("source_slope = 89\n"), (test::source_dir() / "sample_dem/rockfall_release.gpkg").string(),
                "auto"),
       "no cell steeper than 89.0 degrees"},
      {replaced(sample_study(), "project = \"off\"\n[[mudflow]]", "project = \"off\"\nintensity = \"none\"\n[[mudflow]]"),
       "the hazard map needs every scenario's intensity"},
  };
  for (const auto& c : cases) {
    const fs::path study = write_study(folder, c.text);
    const test::ProgramResult run = test::run_talus({"study", study.string(), "--out", "out"}, folder);
    EXPECT_EQ(run.exit_code, 2) << c.expected << "\n" << run.out << run.err;
    EXPECT_NE(run.err.find(c.expected), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(fs::exists(folder / "out")) << c.expected;
  }
  // An output folder that holds other files is not a study's to write into.
  fs::create_directories(folder / "busy");
  std::ofstream(folder / "busy" / "notes.txt") << "keep\n";
  const test::ProgramResult busy =
      test::run_talus({"study", write_study(folder, sample_study()).string(), "--out", "busy"}, folder);
  EXPECT_EQ(busy.exit_code, 2) << busy.err;
  EXPECT_NE(busy.err.find("not a Talus study (notes.txt)"), std::string::npos) << busy.err;
  EXPECT_EQ(std::distance(fs::directory_iterator(folder / "busy"), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace talus
