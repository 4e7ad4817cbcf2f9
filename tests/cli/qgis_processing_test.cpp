// The QGIS Processing provider (issue 17, item 9; gis/qgis/talus_processing, docs/qgis.md):
// headless in PyQGIS as the toolbox runs it, and through `qgis_process run` on the sample scene.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

const fs::path kPython = "/usr/bin/python3";
const fs::path kQgisProcess = "/usr/bin/qgis_process.bin";  // the wrapper passes an option 3.22 refuses

std::string quoted(const std::string& text) { return "'" + text + "'"; }

int exit_code(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(QgisProcessing, ToolboxAlgorithmsRunTalusReportProgressRefuseBadValuesAndQueueStyledLayers) {
  if (!fs::exists(kPython)) GTEST_SKIP() << kPython << " (with python3-qgis) is not installed";
  const auto work = test::fresh_folder("qgis_processing");
  const std::string command = kPython.string() + " " +
                              quoted((test::source_dir() / "tests/gis/qgis/run_processing_provider.py").string()) + " " +
                              quoted((test::source_dir() / "gis/qgis").string()) + " " + quoted(test::talus_exe().string()) +
                              " " + quoted((test::source_dir() / "sample_dem").string()) + " " + quoted(work.string());
  EXPECT_EQ(exit_code(command), 0);
}

// The install steps of docs/qgis.md in a fresh QGIS profile: the plugin folder on QGIS_PLUGINPATH,
// `qgis_process plugins enable talus_processing`, then one rock-fall run from the command line.
TEST(QgisProcessing, QgisProcessRunsTheRockFallOnTheSampleScene) {
  if (!fs::exists(kQgisProcess)) GTEST_SKIP() << kQgisProcess << " is not installed";
  const auto work = test::fresh_folder("qgis_process");
  const auto sample = test::source_dir() / "sample_dem";
  const std::string environment = "HOME=" + quoted((work / "home").string()) +
                                  " QGIS_PLUGINPATH=" + quoted((test::source_dir() / "gis/qgis").string()) +
                                  " TALUS_PROGRAM=" + quoted(test::talus_exe().string()) +
                                  " QT_QPA_PLATFORM=offscreen GDAL_PAM_ENABLED=NO ";
  fs::create_directories(work / "home");
  ASSERT_EQ(exit_code(environment + kQgisProcess.string() + " plugins enable talus_processing > /dev/null 2>&1"), 0);
  const auto out = work / "out";
  const std::string run = environment + kQgisProcess.string() + " run talus:rockfall -- DEM=" +
                          quoted((sample / "dem.tif").string()) + " RELEASE=" +
                          quoted((sample / "rockfall_release.gpkg").string()) + " run__runs=2 OUTPUT=" +
                          quoted(out.string()) + " > " + quoted((work / "log").string()) + " 2>&1";
  ASSERT_EQ(exit_code(run), 0);
  EXPECT_TRUE(fs::exists(out / "energy_max.tif"));
  EXPECT_TRUE(fs::exists(out / "energy_max.qml"));
  EXPECT_TRUE(fs::exists(out / "run.json"));
}

}  // namespace
}  // namespace talus
