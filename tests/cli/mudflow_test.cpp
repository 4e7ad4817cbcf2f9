// `talus mudflow` end to end (issue 5, "Done when"): every layer of the contract
// (tests/support/layer_contract.hpp) on the sample scene and on Mount St Helens, styled in QGIS;
// run.json's counts and the volume balance; the same layers at 1 and 2 threads; entrainment
// from an erodible raster; particle snapshots; bad inputs refused with one line and nothing
// written.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "layer_contract.hpp"
#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "talus/gis/folder_manifest.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

const char* const kLayers[] = {"flow_depth_max", "velocity_max", "pressure_max", "deposit_depth", "arrival_time"};

// The sample scene with 5 m particles (a run of one to a few seconds).
std::vector<std::string> sample_arguments(const fs::path& out, const std::string& threads) {
  const auto sample = test::source_dir() / "sample_dem";
  return {"mudflow", "--dem", (sample / "dem.tif").string(), "--lithology", (sample / "lithology.tif").string(),
          "--vegetation", (sample / "vegetation.tif").string(), "--release", (sample / "mudflow_release.gpkg").string(),
          "--out", out.string(), "--particle-size", "5", "--threads", threads};
}

std::vector<std::string> with(std::vector<std::string> arguments, const std::vector<std::string>& more) {
  arguments.insert(arguments.end(), more.begin(), more.end());
  return arguments;
}

// A raster on the sample DEM's grid (EPSG:31287, 5 m cells, 260 x 400).
test::RasterFixture sample_grid_fixture() {
  test::RasterFixture grid;
  grid.width = 260;
  grid.height = 400;
  grid.x0 = 255302.0828;
  grid.y0 = 380605.9942;
  grid.cell = 5.0;
  grid.crs = "EPSG:31287";
  return grid;
}

int run_python(const std::string& arguments) { return std::system(("/usr/bin/python3 " + arguments).c_str()); }

nlohmann::json read_json(const fs::path& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

// Sum of a layer's valid values times the cell area (m3 for depth layers).
double layer_volume(const fs::path& layer, double cell_area) {
  double sum = 0;
  for (const float value : test::read_band(layer)) sum += value > 0 ? value : 0;
  return sum * cell_area;
}

constexpr double kSampleCellArea = 25.0;  // m2: 5 m cells

// (deposited + outflow) / (released + entrained) - 1 from run.json.
double volume_balance(const nlohmann::json& record) {
  const auto& v = record["volumes_m3"];
  return (v["deposited"].get<double>() + v["outflow"].get<double>()) /
             (v["released"].get<double>() + v["entrained"].get<double>()) -
         1.0;
}

class SampleMudflow : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = test::fresh_folder("mudflow_sample");
    result_ = test::run_talus(with(sample_arguments(root_ / "out", "1"), {"--snapshots", "10"}), root_);
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  static fs::path root_;
  static test::ProgramResult result_;
};
fs::path SampleMudflow::root_;
test::ProgramResult SampleMudflow::result_;

TEST_F(SampleMudflow, WritesEveryLayerOfTheContract) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  EXPECT_EQ(test::layer_contract_problems("mudflow", root_ / "out", test::source_dir() / "sample_dem/dem.tif"),
            test::kNoProblems);
  EXPECT_NE(result_.out.find("Layers written to"), std::string::npos);
  EXPECT_NE(result_.err.find("Progress: 100% (mud flow: simulated "), std::string::npos) << result_.err;
  EXPECT_FALSE(fs::exists(root_ / "out" / "erosion_depth.tif"));  // no --erodible
  for (const auto& entry : fs::directory_iterator(root_ / "out")) {
    if (entry.path().filename() == gis::kFolderManifestName) continue;
    EXPECT_NE(entry.path().filename().string().front(), '.') << "temporary file left: " << entry.path();
  }
  // The flow leaves the release: something deposits and some cell is reached after the start.
  EXPECT_GT(layer_volume(root_ / "out" / "deposit_depth.tif", kSampleCellArea), 0.0);
  const auto arrival = test::read_band(root_ / "out" / "arrival_time.tif");
  EXPECT_GT(*std::max_element(arrival.begin(), arrival.end()), 0.0f);
}

TEST_F(SampleMudflow, RecordsCountsAndConservesVolume) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const nlohmann::json record = read_json(root_ / "out" / "run.json");
  for (const char* role : {"dem", "lithology", "vegetation", "release"}) {
    EXPECT_EQ(record["inputs"][role]["sha256"].get<std::string>().size(), 64u) << role;
  }
  for (const char* section :
       {"run", "mud", "adaptivity", "time_steps", "contact", "rheology", "deposition", "entrainment", "outputs"}) {
    EXPECT_TRUE(record["parameters"].contains(section)) << section;
  }
  EXPECT_EQ(record["parameters"]["mud"]["particle_size"], 5.0);
  EXPECT_EQ(record["parameters"]["rheology"]["rheology"], "voellmy");
  EXPECT_EQ(record["threads"], 1);
  const auto& counts = record["counts"];
  EXPECT_GT(counts["particles"]["initial"].get<int>(), 0);
  EXPECT_GE(counts["particles"]["peak"].get<int>(), counts["particles"]["initial"].get<int>());
  EXPECT_GT(counts["particle_steps"].get<double>(), 0.0);
  EXPECT_GT(counts["coarse_steps"].get<double>(), 0.0);
  for (const char* key : {"splits", "merges", "guard_retries"}) EXPECT_TRUE(counts.contains(key)) << key;
  EXPECT_TRUE(record["end"].contains("reason"));
  // The history: one point at the start and after every coarse step, its last at the end.
  const auto& history = record["history"];
  ASSERT_EQ(history["time_s"].size(), counts["coarse_steps"].get<std::size_t>() + 1);
  EXPECT_NEAR(history["time_s"].back().get<double>(), record["end"]["simulated_time_s"].get<double>(), 1e-9);
  EXPECT_EQ(history["kinetic_energy_j"].size(), history["time_s"].size());
  EXPECT_LE(record["conservation"]["adaptivity_mass_change"].get<double>(), 1e-12);  // issue 5: 1e-12
  for (const char* phase : {"read_inputs", "simulate", "write_layers"}) EXPECT_TRUE(record["timings_s"].contains(phase));
  // The release polygon: 321 cells of 5 m (8025 m2) at 1.8 m normal to the slope, i.e.
  // sum 1.8 m x 25 m2 / cos(theta) = 17,310 m3 with the slopes of GDAL's gdaldem (Horn's
  // method; 14,445 m3 as vertical columns). Talus takes the slope's central differences: 0.5%.
  EXPECT_NEAR(record["volumes_m3"]["released"].get<double>(), 17310.0, 0.005 * 17310.0);
  // Issue 37, item 4: run.json says how the depths were read and what the other reading gives.
  EXPECT_EQ(record["release"]["depth_measured"], "normal");
  EXPECT_EQ(record["release"]["release_thickness"], "auto");
  EXPECT_NEAR(record["release"]["volume_m3"]["normal"].get<double>(), record["volumes_m3"]["released"].get<double>(),
              1e-6 * 17310.0);
  EXPECT_NEAR(record["release"]["volume_m3"]["vertical"].get<double>(), 1.8 * 8025.0, 1e-3);
  // Issue 5: deposited volume equals released plus entrained volume within 2 %.
  EXPECT_NEAR(volume_balance(record), 0.0, 0.02);
  // The deposit layer holds the volume left on the DEM as depths normal to the ground, so depth
  // x cell area sums to that volume times the cosines of the slopes under it: at most the
  // volume (Float32 cells: 1e-4 relative), at least 0.7 of it (mud deposits on slopes under 45°).
  const double deposit_ratio = layer_volume(root_ / "out" / "deposit_depth.tif", kSampleCellArea) /
                               record["volumes_m3"]["deposited"].get<double>();
  EXPECT_LE(deposit_ratio, 1.0 + 1e-4);
  EXPECT_GE(deposit_ratio, 0.7);
}

// Issue 18, item 4: a flow still moving at [run] duration is reported in run.json's problems and
// on the terminal, with the particles still flowing and the kinetic energy left; the sample's
// full run, which ends by the energy criterion, reports none.
TEST_F(SampleMudflow, AFlowCutShortByTheTimeLimitIsAProblem) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const nlohmann::json finished = read_json(root_ / "out" / "run.json");
  EXPECT_EQ(finished["end"]["reason"], "energy");
  EXPECT_TRUE(finished["problems"].empty()) << finished["problems"].dump();

  const auto root = test::fresh_folder("mudflow_time_limit");
  const auto cut = test::run_talus(with(sample_arguments(root / "out", "1"), {"--duration", "5"}), root);
  ASSERT_EQ(cut.exit_code, 0) << cut.err;
  const nlohmann::json record = read_json(root / "out" / "run.json");
  EXPECT_EQ(record["end"]["reason"], "duration");
  ASSERT_EQ(record["problems"].size(), 1u) << record["problems"].dump();
  const std::string line = record["problems"][0].get<std::string>();
  const auto flowing = record["history"]["flowing"].back().get<std::size_t>();
  EXPECT_EQ(line.rfind("mud flow: " + std::to_string(flowing) + " particles were still flowing at the time limit "
                       "([run] duration = 5 s)", 0), 0u) << line;
  EXPECT_NE(line.find("raise [run] duration"), std::string::npos) << line;
  EXPECT_NE(cut.out.find("problem: " + line + "\n"), std::string::npos) << cut.out;
  fs::remove_all(root);
}

TEST_F(SampleMudflow, LayersOpenStyledInQgis) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  std::string arguments = (test::source_dir() / "tests/gis/qgis/check_layer_in_qgis.py").string() + " EPSG:31287";
  const std::map<std::string, std::string> descriptions = {{"flow_depth_max", "Maximum flow depth (m)"},
                                                           {"velocity_max", "Maximum velocity (m/s)"},
                                                           {"pressure_max", "Maximum impact pressure (kPa)"},
                                                           {"deposit_depth", "Deposit depth (m)"},
                                                           {"arrival_time", "Arrival time of the flow (s)"},
                                                           {"intensity", "Intensity class by foen-2016"}};
  for (const auto& [layer, description] : descriptions) {
    arguments += " " + (root_ / "out" / (layer + ".tif")).string() + " '" + description + "'";
  }
  EXPECT_EQ(run_python(arguments), 0);
}

// Issue 20, item 7: the progress lines follow simulated time to the expected end (the energy
// criterion ends this run before --duration), never go back, and say what is left.
TEST_F(SampleMudflow, ProgressFollowsTimeToTheExpectedEnd) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  std::vector<int> percents;
  std::istringstream lines(result_.err);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("Progress: ", 0) != 0) continue;
    percents.push_back(std::stoi(line.substr(10)));
    if (percents.back() < 100) {
      EXPECT_NE(line.find("(mud flow: simulated "), std::string::npos) << line;
      EXPECT_NE(line.find(" s of about "), std::string::npos) << line;
      EXPECT_NE(line.find(" s left)"), std::string::npos) << line;
    }
  }
  ASSERT_GE(percents.size(), 2u) << result_.err;
  EXPECT_TRUE(std::is_sorted(percents.begin(), percents.end())) << result_.err;
  EXPECT_EQ(percents.back(), 100);
  // No jump to the end: the line before the last is at 80% or more (before issue 20, 70%).
  EXPECT_GE(percents[percents.size() - 2], 80) << result_.err;
}

TEST_F(SampleMudflow, SnapshotsHoldTheParticlesWithTheirTime) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const nlohmann::json record = read_json(root_ / "out" / "run.json");
  EXPECT_TRUE(fs::exists(root_ / "out" / "particles.qml"));
  GDALAllRegister();
  GDALDatasetUniquePtr dataset(GDALDataset::Open((root_ / "out" / "particles.gpkg").c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  ASSERT_TRUE(dataset);
  OGRLayer* layer = dataset->GetLayerByName("particles");
  ASSERT_NE(layer, nullptr);
  ASSERT_GE(layer->GetLayerDefn()->GetFieldIndex("time_s"), 0);
  std::map<double, double> mass_at;  // kg per snapshot time (s)
  for (auto& feature : *layer) mass_at[feature->GetFieldAsDouble("time_s")] += feature->GetFieldAsDouble("mass_kg");
  // A snapshot at release, one every 10 s, and one at the end.
  const double end = record["end"]["simulated_time_s"].get<double>();
  ASSERT_FALSE(mass_at.empty());
  EXPECT_EQ(mass_at.begin()->first, 0.0);
  EXPECT_NEAR(mass_at.rbegin()->first, end, 1e-9);
  EXPECT_EQ(static_cast<double>(mass_at.size()), std::ceil(end / 10.0) + 1.0);
  EXPECT_EQ(record["counts"]["snapshots"].get<std::size_t>(), mass_at.size());
  // At release the particles carry the released mud: rho0 x released volume (1e-9 relative).
  const double released_mass = 2000.0 * record["volumes_m3"]["released"].get<double>();
  EXPECT_NEAR(mass_at.begin()->second / released_mass, 1.0, 1e-9);
}

// Issue 5: same seed, identical layers at 1 and 2 threads, bit for bit.
TEST(MudflowThreads, SameLayersAtOneAndTwoThreads) {
  const auto root = test::fresh_folder("mudflow_threads");
  for (const char* threads : {"1", "2"}) {
    const auto result = test::run_talus(sample_arguments(root / threads, threads), root);
    ASSERT_EQ(result.exit_code, 0) << result.err;
  }
  for (const char* layer : kLayers) {
    const auto one = test::read_band(root / "1" / (std::string(layer) + ".tif"));
    const auto two = test::read_band(root / "2" / (std::string(layer) + ".tif"));
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(float)), 0) << layer << " differs";
  }
}

// 0.5 m of erodible material in the gully: the cells a run without it flowed through.
TEST(MudflowErosion, EntrainsFromTheErodibleRaster) {
  const auto root = test::fresh_folder("mudflow_erosion");
  const auto plain = test::run_talus(sample_arguments(root / "plain", "1"), root);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const auto path = test::read_band(root / "plain" / "flow_depth_max.tif");
  test::RasterFixture gully = sample_grid_fixture();
  gully.value = [&](int c, int r) { return path[static_cast<std::size_t>(r * 260 + c)] > 0.0f ? 0.5 : 0.0; };
  test::write_raster(root / "erodible.tif", gully);

  const auto eroding = test::run_talus(
      with(sample_arguments(root / "eroding", "1"), {"--erodible", (root / "erodible.tif").string()}), root);
  ASSERT_EQ(eroding.exit_code, 0) << eroding.err;
  EXPECT_EQ(test::layer_contract_problems("mudflow", root / "eroding", test::source_dir() / "sample_dem/dem.tif"),
            test::kNoProblems);
  ASSERT_TRUE(fs::exists(root / "eroding" / "erosion_depth.tif"));
  const nlohmann::json record = read_json(root / "eroding" / "run.json");
  EXPECT_EQ(record["inputs"]["erodible"]["sha256"].get<std::string>().size(), 64u);
  const double entrained = record["volumes_m3"]["entrained"].get<double>();
  EXPECT_GT(entrained, 0.0);
  EXPECT_NEAR(volume_balance(record), 0.0, 0.02);  // issue 5: within 2 %
  // The erosion layer holds the entrained volume (Float32 cells: 1e-4 relative), never more than
  // the 0.5 m there was (plus Float32 rounding).
  EXPECT_NEAR(layer_volume(root / "eroding" / "erosion_depth.tif", kSampleCellArea) / entrained, 1.0, 1e-4);
  const auto eroded = test::read_band(root / "eroding" / "erosion_depth.tif");
  EXPECT_LE(*std::max_element(eroded.begin(), eroded.end()), 0.5f + 1e-6f);
  EXPECT_EQ(run_python((test::source_dir() / "tests/gis/qgis/check_layer_in_qgis.py").string() + " EPSG:31287 " +
                       (root / "eroding" / "erosion_depth.tif").string() + " 'Eroded depth (m)'"),
            0);
}

// Issue 5, "Done when": Mount St Helens 2021 with the landslide depth raster (negative depths)
// in local coordinates.
TEST(MudflowStHelens, WritesEveryLayerInLocalCoordinates) {
  const auto root = test::fresh_folder("mudflow_sthelens");
  const auto data = test::data_dir() / "sthelens2021";
  const auto result = test::run_talus({"mudflow", "--dem", (data / "pre_runout_DEM.asc").string(), "--release",
                                       (data / "landslide_depth.asc").string(), "--crs", "local", "--out",
                                       (root / "out").string(), "--threads", "1"},
                                      root);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(test::layer_contract_problems("mudflow", root / "out", data / "pre_runout_DEM.asc"), test::kNoProblems);
  const nlohmann::json record = read_json(root / "out" / "run.json");
  // Issue 37, item 4: the raster's depths are negative numbers, the surface lowering of a DEM of
  // difference, so they are read as vertical depths: the released volume is the sum of |d| A.
  double lowering = 0;  // m3
  for (const float depth : test::read_band(data / "landslide_depth.asc")) {
    if (depth < 0.0f && depth != -9999.0f) lowering -= static_cast<double>(depth) * 100.0;
  }
  EXPECT_EQ(record["release"]["depth_measured"], "vertical");
  EXPECT_NE(record["release"]["reason"].get<std::string>().find("DEM of difference"), std::string::npos);
  EXPECT_NEAR(record["release"]["volume_m3"]["vertical"].get<double>(), lowering, 1e-6 * lowering);
  EXPECT_NEAR(record["volumes_m3"]["released"].get<double>(), lowering, 1e-6 * lowering);
  EXPECT_GT(record["release"]["volume_m3"]["normal"].get<double>(), lowering);
  EXPECT_NE(result.out.find("Release: depths read as vertical depths"), std::string::npos) << result.out;
  EXPECT_NEAR(volume_balance(record), 0.0, 0.02);
  GDALAllRegister();
  GDALDatasetUniquePtr layer(GDALDataset::Open((root / "out" / "flow_depth_max.tif").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(layer);
  EXPECT_EQ(layer->GetSpatialRef(), nullptr);  // local coordinates: no CRS
}

// Bad inputs: exit code 2, one line on stderr naming the problem, nothing written.
// Issue 17, item 7: a 0/1 mask used as a mud-flow release used to become 1 m of mud. It is
// refused unless --depth gives the depth; --depth-field names the attribute of a vector release
// (AvaFrame's `thickness`), and --depth replaces whatever depth the file holds.
TEST(MudflowReleaseDepth, AMaskNeedsADepthAndTheDepthFieldNamesTheAttribute) {
  const auto root = test::fresh_folder("mudflow_release_depth");
  test::RasterFixture mask = sample_grid_fixture();  // 1 on the gully release's 9 x 9 cells
  mask.integer = true;
  mask.nodata = -1;
  mask.value = [](int col, int row) { return (col >= 64 && col <= 72 && row >= 21 && row <= 29) ? 1.0 : 0.0; };
  test::write_raster(root / "mask.tif", mask);
  const std::string polygon = "POLYGON((255625 380500,255665 380500,255665 380460,255625 380460,255625 380500))";
  test::write_layer(root / "thickness.gpkg", "EPSG:31287", {{"thickness"}}, {{polygon, {"1.5"}}});
  test::write_vector(root / "depth.gpkg", "EPSG:31287", {{polygon, 1.5}}, true);

  const auto run = [&](const std::string& release, const std::string& out, const std::vector<std::string>& more) {
    auto arguments = with(sample_arguments(root / out, "2"), {"--duration", "2"});
    *(std::find(arguments.begin(), arguments.end(), "--release") + 1) = (root / release).string();
    return test::run_talus(with(arguments, more), root);
  };
  const auto released = [&](const std::string& out) {
    return read_json(root / out / "run.json")["volumes_m3"]["released"].get<double>();
  };

  const auto refused_mask = run("mask.tif", "mask_refused", {});
  EXPECT_EQ(refused_mask.exit_code, 2);
  EXPECT_EQ(refused_mask.err,
            "talus: error: " + (root / "mask.tif").string() +
                " (release): holds only 0 and 1, a mask, not depths; give the release depth with --depth M (m), or a "
                "raster of depths (m)\n");
  EXPECT_FALSE(fs::exists(root / "mask_refused"));
  ASSERT_EQ(run("mask.tif", "mask_1.5", {"--depth", "1.5"}).exit_code, 0);
  ASSERT_EQ(run("mask.tif", "mask_3", {"--depth", "3"}).exit_code, 0);
  EXPECT_GT(released("mask_1.5"), 81 * 25.0 * 1.5);  // 81 cells of 25 m2, thicker than 1.5 m on the slope
  EXPECT_NEAR(released("mask_3") / released("mask_1.5"), 2.0, 1e-9);

  const auto refused_field = run("thickness.gpkg", "thickness_refused", {});
  EXPECT_EQ(refused_field.exit_code, 2);
  EXPECT_NE(refused_field.err.find("(release): layer 'release' has no `depth` attribute; a mud-flow release needs the "
                                   "release depth (m) of each polygon or point: name its attribute with --depth-field "
                                   "NAME, or give one depth with --depth M"),
            std::string::npos)
      << refused_field.err;
  ASSERT_EQ(run("thickness.gpkg", "thickness", {"--depth-field", "thickness"}).exit_code, 0);
  ASSERT_EQ(run("depth.gpkg", "depth", {}).exit_code, 0);
  ASSERT_EQ(run("thickness.gpkg", "uniform", {"--depth", "1.5"}).exit_code, 0);
  EXPECT_EQ(released("thickness"), released("depth"));
  EXPECT_EQ(released("uniform"), released("depth"));
  EXPECT_EQ(read_json(root / "thickness" / "run.json")["parameters"]["mud"]["depth_field"], "thickness");

  const auto both = run("thickness.gpkg", "both", {"--depth", "1.5", "--depth-field", "thickness"});
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_EQ(both.err, "talus: error: --depth-field thickness: give either a depth attribute or one release depth, not both\n");
}

TEST(MudflowUsage, RefusesBadInputsWithOneLineAndWritesNothing) {
  const auto root = test::fresh_folder("mudflow_bad");
  test::write_vector(root / "no_depth.gpkg", "EPSG:31287",
                     {{"POLYGON((255625 380500,255665 380500,255665 380460,255625 380460,255625 380500))", 0}}, false);
  // Depths that are no release depth (issue 18, item 2): far too deep, infinite, a raster in cm.
  const std::string polygon = "POLYGON((255625 380500,255665 380500,255665 380460,255625 380460,255625 380500))";
  test::write_vector(root / "depth_5000.gpkg", "EPSG:31287", {{polygon, 5000.0}}, true);
  test::write_vector(root / "depth_inf.gpkg", "EPSG:31287", {{polygon, std::numeric_limits<double>::infinity()}}, true);
  test::write_vector(root / "depth_negative.gpkg", "EPSG:31287", {{polygon, -1e9}}, true);
  test::RasterFixture centimetres;
  centimetres.x0 = 255600.0;
  centimetres.y0 = 380500.0;
  centimetres.cell = 5.0;
  centimetres.crs = "EPSG:31287";
  centimetres.value = [](int c, int r) { return c > 5 && c < 12 && r > 5 && r < 12 ? 180.0 : 0.0; };
  test::write_raster(root / "depth_cm.tif", centimetres);
  std::ofstream(root / "bad_density.toml") << "[mud]\ndensity = 50\n";
  std::ofstream(root / "old_friction.toml") << "[rheology]\nfriction_factor = 0.5\n";
  std::ofstream(root / "bad_friction.toml") << "[rheology]\nfriction = 1.5\n";
  std::ofstream(root / "bad_material.toml") << "[mud]\nmaterial = \"honey\"\n";
  std::ofstream(root / "number_as_boolean.toml") << "[contact]\nstep_normal = 1\n";
  const auto out = root / "out";
  const auto sample = sample_arguments(out, "2");
  struct Case {
    std::vector<std::string> arguments;
    std::string message;
  };
  const auto replaced = [&](std::size_t k, const std::string& value) {
    auto arguments = sample;
    arguments[k] = value;
    return arguments;
  };
  auto release_replaced = sample;
  release_replaced[8] = (root / "no_depth.gpkg").string();
  auto size_zero = sample;
  *(std::find(size_zero.begin(), size_zero.end(), "--particle-size") + 1) = "0";
  auto dem_missing = sample;
  dem_missing[2] = (root / "missing.tif").string();
  const std::vector<Case> cases = {
      {release_replaced, "no_depth.gpkg (release): layer 'release' has no `depth` attribute"},
      {size_zero, "--particle-size 0: expected 0.05-100 m"},
      {with(sample, {"--adaptive", "maybe"}), "--adaptive maybe: use on or off"},
      {with(sample, {"--rheology", "honey"}), "--rheology honey: use viscous, coulomb, voellmy or bingham"},
      {with(sample, {"--snapshots", "0"}),
       "--snapshots 0: expected an interval of at least 0.01 s"},
      {with(sample, {"--snapshots", "1e-6"}), "--snapshots 1e-06: expected 0 (none) or 0.01-86400 s"},
      {with(sample, {"--snapshots", "0.01", "--duration", "5000"}),
       "--snapshots 0.01: expected at most 100000 snapshots over --duration"},
      {with(sample, {"--duration", "-5"}), "--duration -5: expected > 0 and <= 86400 s"},
      {with(sample, {"--scenario", (root / "bad_density.toml").string()}),
       "bad_density.toml (scenario): [mud] density 50: expected 100-3000 kg/m3"},
      {with(sample, {"--scenario", (root / "old_friction.toml").string()}),
       "old_friction.toml (scenario): [rheology] friction_factor: no longer used: give [rheology] friction, the friction "
       "coefficient mu itself (0-1)"},
      {with(sample, {"--scenario", (root / "bad_friction.toml").string()}),
       "bad_friction.toml (scenario): [rheology] friction 1.5: expected 0-1"},
      {with(sample, {"--material", "honey"}),
       "--material honey: expected one of debris-flow, granular, mud-flow, rock-avalanche, snow-avalanche"},
      {with(sample, {"--scenario", (root / "bad_material.toml").string()}),
       "bad_material.toml (scenario): [mud] material honey: expected one of debris-flow, granular, mud-flow"},
      {with(sample, {"--scenario", (root / "number_as_boolean.toml").string()}),
       "number_as_boolean.toml (scenario): [contact] step_normal must be true or false"},
      {dem_missing, "missing.tif (DEM): file not found"},
      {with(sample, {"--erodible", (root / "missing_erodible.tif").string()}), "missing_erodible.tif (erodible): file not found"},
      {with(sample, {"--depth", "0.0001"}), "--depth 0.0001: expected 0 (the release file's depths) or 0.01-100 m"},
      {with(sample, {"--depth", "nan"}), "--depth nan: expected 0 (the release file's depths) or 0.01-100 m"},
      {with(sample, {"--depth", "500"}), "--depth 500: expected 0 (the release file's depths) or 0.01-100 m"},
      {replaced(8, (root / "depth_5000.gpkg").string()),
       "depth_5000.gpkg (release): feature 1 of layer 'release' has a release depth (depth) of 5000 m; expected at most 100 m"},
      {replaced(8, (root / "depth_inf.gpkg").string()), "has a release depth (depth) of inf m"},
      {replaced(8, (root / "depth_negative.gpkg").string()), "has a release depth (depth) of -1e+09 m"},
      {replaced(8, (root / "depth_cm.tif").string()),
       "depth_cm.tif (release): a release depth of 180 m; expected depths of at most 100 m (are they in centimetres?)"},
      {with(sample, {"--snapshots", "10", "--start-time", "tomorrow"}),
       "--start-time tomorrow: expected a date-time YYYY-MM-DDTHH:MM:SS, years 1000-9999"},
  };
  for (const Case& c : cases) {
    const auto result = test::run_talus(c.arguments, root);
    EXPECT_EQ(result.exit_code, 2) << c.message;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_EQ(result.err.rfind("talus: error: ", 0), 0u) << result.err;
    EXPECT_NE(result.err.find(c.message), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(out)) << c.message;
  }
}

}  // namespace
}  // namespace talus

namespace talus {
namespace {

// Issue 19, item 4 (docs/study.md, "Tiles"): a region whose ground does not fit runs the flow on a
// window around its release; with a halo the mud never crosses, the layers are the whole run's,
// bit for bit, entrainment included; mud that crosses a narrow halo's edge is reported.
TEST(MudflowWindow, AFlowOnItsWindowEqualsTheWholeRunBitForBit) {
  const auto root = test::fresh_folder("mudflow_window");
  test::RasterFixture bed = sample_grid_fixture();
  bed.value = [](int, int) { return 0.5; };
  test::write_raster(root / "erodible.tif", bed);
  std::ofstream(root / "window.toml") << "[tiles]\nsize = 30\nhalo = 1500\n";
  std::ofstream(root / "narrow.toml") << "[tiles]\nsize = 30\nhalo = 100\n";
  const std::vector<std::string> erodible = {"--erodible", (root / "erodible.tif").string()};
  const auto whole = test::run_talus(with(sample_arguments(root / "whole", "2"), erodible), root);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto windowed = test::run_talus(
      with(with(sample_arguments(root / "window", "2"), erodible), {"--scenario", (root / "window.toml").string()}), root);
  ASSERT_EQ(windowed.exit_code, 0) << windowed.err;
  EXPECT_NE(windowed.out.find("Window: "), std::string::npos) << windowed.out;
  const nlohmann::json record = read_json(root / "window" / "run.json");
  EXPECT_TRUE(record["tiles"].is_object());
  EXPECT_GT(record["volumes_m3"]["entrained"].get<double>(), 0.0);
  EXPECT_EQ(record["volumes_m3"]["halo_outflow"].get<double>(), 0.0);
  for (const std::string layer : {"flow_depth_max", "velocity_max", "pressure_max", "deposit_depth", "arrival_time",
                                  "erosion_depth", "intensity"}) {
    EXPECT_EQ(test::read_band(root / "window" / (layer + ".tif")), test::read_band(root / "whole" / (layer + ".tif")))
        << layer;
  }
  const auto narrow = test::run_talus(with(sample_arguments(root / "narrow", "2"), {"--scenario", (root / "narrow.toml").string()}), root);
  ASSERT_EQ(narrow.exit_code, 0) << narrow.err;
  const nlohmann::json cut = read_json(root / "narrow" / "run.json");
  EXPECT_GT(cut["volumes_m3"]["halo_outflow"].get<double>(), 0.0);
  EXPECT_NE(narrow.out.find("crossed the edge of the flow's window ([tiles] halo = 100 m"), std::string::npos) << narrow.out;
}

}  // namespace
}  // namespace talus
