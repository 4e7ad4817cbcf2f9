// Validation against a real experiment (issue 16, Deliver 4): the Tschamut 2014 rock-fall tests
// (SLF; Volkwein and Gerber 2018, doi:10.16904/envidat.34). The 18 calibration runs of
// validation/tschamut2014/ release their real blocks (axes, mass, initial velocity per run) on
// the terrain proxy, with the documented meadow parameters of validation/tschamut2014/
// (materials.toml, scenario.toml), in fast and in full mode, 5 runs per release point. The
// simulated runouts (straight horizontal distance from the release to the stop, as the observed
// `observed_runout_m`) are compared with the observed ones; docs/validation.md gives the figures.
#include <gtest/gtest.h>

#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

fs::path case_dir() { return test::source_dir() / "validation" / "tschamut2014"; }

// Horizontal runouts (m) and travel azimuths (degrees clockwise from north) of a set of runs.
struct Runouts {
  std::vector<double> runout;
  std::vector<double> azimuth;
};

void add_run(Runouts& runs, double dx, double dy) {
  runs.runout.push_back(std::hypot(dx, dy));
  if (dx != 0.0 || dy != 0.0) runs.azimuth.push_back(std::fmod(std::atan2(dx, dy) * 180.0 / std::numbers::pi + 360.0, 360.0));
}

// The p-quantile by linear interpolation between order statistics (numpy's default).
double quantile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  const double position = p * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - static_cast<double>(below)) * (values[above] - values[below]);
}

// calibration_runs.csv: release (x, y) and observed deposit (observed_x, observed_y).
Runouts observed_runouts() {
  std::ifstream file(case_dir() / "calibration_runs.csv");
  std::string line;
  std::getline(file, line);
  Runouts runs;
  while (std::getline(file, line)) {
    // Fields: trajectory_id, block_id, x, y, shape, "A,B,C", mass, vx, vy, vz, release_height,
    // observed_x, observed_y, observed_runout_m. The quoted size holds commas: split around it.
    const std::size_t open = line.find('"'), close = line.find('"', open + 1);
    std::vector<std::string> before, after;
    std::stringstream head(line.substr(0, open)), tail(line.substr(close + 2));
    for (std::string field; std::getline(head, field, ',');) before.push_back(field);
    for (std::string field; std::getline(tail, field, ',');) after.push_back(field);
    const double x = std::stod(before[2]), y = std::stod(before[3]);
    add_run(runs, std::stod(after[5]) - x, std::stod(after[6]) - y);
  }
  return runs;
}

// Every line of a run's trajectories.gpkg: its first vertex is the release, its last the stop; a
// rock that never left its release point has a line of one point (no geometry) and counts as 0 m.
Runouts simulated_runouts(const fs::path& out) {
  GDALAllRegister();
  GDALDatasetUniquePtr data(GDALDataset::Open((out / "trajectories.gpkg").c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  Runouts runs;
  if (!data) return runs;
  for (auto& feature : *data->GetLayerByName("trajectories")) {
    const OGRGeometry* geometry = feature->GetGeometryRef();
    if (geometry == nullptr || geometry->IsEmpty()) {
      add_run(runs, 0.0, 0.0);
      continue;
    }
    const OGRLineString* line = geometry->toLineString();
    add_run(runs, line->getX(line->getNumPoints() - 1) - line->getX(0), line->getY(line->getNumPoints() - 1) - line->getY(0));
  }
  return runs;
}

std::vector<std::string> case_arguments(const fs::path& out, const std::string& mode) {
  const fs::path c = case_dir();
  return {"rockfall", "--dem", (c / "terrain.asc").string(), "--crs", "local", "--release",
          (c / "calibration_runs.vrt").string(), "--materials", (c / "materials.toml").string(), "--scenario",
          (c / "scenario.toml").string(), "--mode", mode, "--out", out.string()};
}

class Tschamut2014 : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = test::fresh_folder("tschamut2014");
    for (const std::string mode : {"fast", "full"}) results_[mode] = test::run_talus(case_arguments(root_ / mode, mode), root_);
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  static fs::path root_;
  static std::map<std::string, test::ProgramResult> results_;
};
fs::path Tschamut2014::root_;
std::map<std::string, test::ProgramResult> Tschamut2014::results_;

// The observed calibration runs as docs/validation.md quotes them: median 100.7 m, p05 43.8 m,
// p95 108.1 m, azimuth 148.8 degrees (the CSV is the 18 calibration runs, nothing else).
TEST_F(Tschamut2014, ObservedCalibrationRunsAreTheDocumentedOnes) {
  const Runouts observed = observed_runouts();
  ASSERT_EQ(observed.runout.size(), 18u);
  EXPECT_NEAR(quantile(observed.runout, 0.5), 100.7, 0.05);
  EXPECT_NEAR(quantile(observed.runout, 0.05), 43.8, 0.05);
  EXPECT_NEAR(quantile(observed.runout, 0.95), 108.1, 0.05);
  EXPECT_NEAR(quantile(observed.azimuth, 0.5), 148.8, 0.05);
}

// Done when of issue 16: the simulated median runout within 10% of the observed, in both modes
// with the same parameters; the travel direction within 10 degrees. The spread is only held to a
// factor of 2 (p05 and p95 within 0.5-2 times the observed): the terrain proxy is known only
// where blocks were tracked, and beyond the deposits (about 115 m from the releases) it is a
// plane of the trend's 25.6 degrees, on which simulated blocks that pass the deposits' bench
// roll on; and 18 runs fix the observed tails poorly (docs/validation.md).
TEST_F(Tschamut2014, SimulatedRunoutsMatchTheObservedInBothModes) {
  const Runouts observed = observed_runouts();
  for (const std::string mode : {"fast", "full"}) {
    ASSERT_EQ(results_[mode].exit_code, 0) << mode << ": " << results_[mode].err;
    const Runouts simulated = simulated_runouts(root_ / mode);
    ASSERT_EQ(simulated.runout.size(), 90u) << mode;
    const double median = quantile(simulated.runout, 0.5);
    std::printf("%s mode: median %.1f m (observed %.1f), p05 %.1f (%.1f), p95 %.1f (%.1f), azimuth %.1f (%.1f)\n",
                mode.c_str(), median, quantile(observed.runout, 0.5), quantile(simulated.runout, 0.05),
                quantile(observed.runout, 0.05), quantile(simulated.runout, 0.95), quantile(observed.runout, 0.95),
                quantile(simulated.azimuth, 0.5), quantile(observed.azimuth, 0.5));
    EXPECT_NEAR(median / quantile(observed.runout, 0.5), 1.0, 0.10) << mode;
    EXPECT_NEAR(quantile(simulated.azimuth, 0.5), quantile(observed.azimuth, 0.5), 10.0) << mode;
    for (const double p : {0.05, 0.95}) {
      const double ratio = quantile(simulated.runout, p) / quantile(observed.runout, p);
      EXPECT_GT(ratio, 0.5) << mode << " p" << 100 * p;
      EXPECT_LT(ratio, 2.0) << mode << " p" << 100 * p;
    }
  }
}

}  // namespace
}  // namespace talus
