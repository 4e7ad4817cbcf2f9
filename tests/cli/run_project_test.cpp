// project.qgz, hillshade.tif and quicklook/*.png of a run (issue 17, item 8; docs/layers.md, "QGIS
// project and quicklooks"): written by default for both processes and checked headless in QGIS;
// `--project off` writes none; without QGIS's Python a run still succeeds with a note; own data
// with --crs line up, a raster release is an overlay, particles are animated (issue 38, item 1).
#include <gtest/gtest.h>

#include <cstdlib>

#include "run_talus.hpp"
#include "talus/gis/folder_manifest.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

const fs::path kPython = "/usr/bin/python3";

std::vector<std::string> sample_run(const std::string& process, const fs::path& out, std::vector<std::string> extra) {
  const auto sample = test::source_dir() / "sample_dem";
  std::vector<std::string> arguments = {process,       "--dem",        (sample / "dem.tif").string(),
                                        "--lithology", (sample / "lithology.tif").string(),
                                        "--release",   (sample / (process + "_release.gpkg")).string(),
                                        "--out",       out.string()};
  if (process == "rockfall") arguments.insert(arguments.end(), {"--runs", "2"});
  if (process == "mudflow") arguments.insert(arguments.end(), {"--particle-size", "5"});
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return arguments;
}

int check_project(const fs::path& out, const std::string& process, const std::string& layers) {
  const auto script = test::source_dir() / "tests/gis/qgis/check_run_project.py";
  const std::string command = kPython.string() + " '" + script.string() + "' '" + out.string() + "' " + process + " " + layers;
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool hidden_files_left(const fs::path& out) {
  for (const auto& entry : fs::directory_iterator(out))
    if (entry.path().filename().string().front() == '.' && entry.path().filename() != gis::kFolderManifestName) return true;
  return false;
}

TEST(RunProject, RockFallProjectOpensInQgisWithItsLayersAndQuicklooks) {
  if (!fs::exists(kPython)) GTEST_SKIP() << kPython << " (with python3-qgis) is not installed";
  const auto root = test::fresh_folder("run_project_rockfall");
  const auto result = test::run_talus(sample_run("rockfall", root / "out", {"--project", "on"}), root);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("QGIS project " + (root / "out" / "project.qgz").string()), std::string::npos) << result.out;
  EXPECT_TRUE(fs::exists(root / "out" / "hillshade.tif"));
  EXPECT_FALSE(hidden_files_left(root / "out"));
  EXPECT_EQ(check_project(root / "out", "rockfall", "intensity energy_p95 reach_probability velocity_max"), 0);
}

TEST(RunProject, MudFlowProjectOpensInQgisWithItsLayersAndQuicklooks) {
  if (!fs::exists(kPython)) GTEST_SKIP() << kPython << " (with python3-qgis) is not installed";
  const auto root = test::fresh_folder("run_project_mudflow");
  const auto result =
      test::run_talus(sample_run("mudflow", root / "out", {"--project", "on", "--snapshots", "30"}), root);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_FALSE(hidden_files_left(root / "out"));
  EXPECT_TRUE(fs::exists(root / "out" / "particles.gpkg"));  // and animated in the project
  EXPECT_EQ(check_project(root / "out", "mudflow", "intensity flow_depth_max velocity_max arrival_time"), 0);
}

// Issue 38, item 1: a DEM and a 0/1 release raster without a CRS, given one by --crs: the
// project, the hillshade and the release are in it, and the release's zeros are transparent.
TEST(RunProject, OwnDataWithCrsFromTheCommandLineLinesUp) {
  if (!fs::exists(kPython)) GTEST_SKIP() << kPython << " (with python3-qgis) is not installed";
  const auto root = test::fresh_folder("run_project_crs");
  const auto norway = test::source_dir() / "data" / "norway_forest";
  const auto result = test::run_talus({"rockfall", "--dem", (norway / "dem_5m_sn1.asc").string(), "--release",
                                       (norway / "rel_sn1.asc").string(), "--crs", "EPSG:25833", "--runs", "1", "--project", "on",
                                       "--out", (root / "out").string()},
                                      root);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(check_project(root / "out", "rockfall", "intensity"), 0) << result.out;
}

TEST(RunProject, OffWritesNoneAndWithoutQgisARunSucceedsWithANote) {
  const auto root = test::fresh_folder("run_project_off");
  const auto off = test::run_talus(sample_run("rockfall", root / "off", {"--project", "off"}), root);
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_FALSE(fs::exists(root / "off" / "project.qgz"));
  EXPECT_FALSE(fs::exists(root / "off" / "quicklook"));

  ::setenv("TALUS_PYTHON", (root / "no-python").c_str(), 1);
  const auto missing = test::run_talus(sample_run("rockfall", root / "missing", {"--project", "on"}), root);
  ::unsetenv("TALUS_PYTHON");
  ASSERT_EQ(missing.exit_code, 0) << missing.err;
  EXPECT_NE(missing.out.find("note: no project.qgz or quicklooks: " + (root / "no-python").string()), std::string::npos)
      << missing.out;
  EXPECT_TRUE(fs::exists(root / "missing" / "energy_max.tif"));
  EXPECT_FALSE(fs::exists(root / "missing" / "project.qgz"));
  EXPECT_FALSE(hidden_files_left(root / "missing"));

  const auto bad = test::run_talus(sample_run("rockfall", root / "bad", {"--project", "maybe"}), root);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--project maybe: use on or off"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace talus
