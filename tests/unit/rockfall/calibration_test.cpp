// Tests of the fast-mode calibration (paper 3.3, "Fast Bounce mode", last paragraph): the
// simple-slope scene, the objective, and the fit, which must recover known coefficients when
// the fast mode is fitted against itself.
#include "talus/rockfall/calibration.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "talus/core/errors.hpp"

namespace talus {
namespace {

double tan_deg(double degrees) { return std::tan(degrees * std::numbers::pi / 180.0); }

TEST(CalibrationGround, CrestSlopeAndRunoutZoneFollowTheScene) {
  CalibrationScene scene;
  const GroundModel ground = calibration_ground(scene, 30.0, GroundMaterial{});
  const double run = scene.slope_length * std::cos(30.0 * std::numbers::pi / 180.0);  // m, horizontal
  // Bilinear interpolation is exact on each plane, away from the two breaks (1e-9 m).
  const double crest = ground.elevation(-scene.crest_length + 1.0, 0.0);
  EXPECT_NEAR(ground.elevation(20.0, 0.0), crest - 20.0 * tan_deg(30.0), 1e-9);
  EXPECT_NEAR(ground.elevation(run - 10.0, 12.0), crest - (run - 10.0) * tan_deg(30.0), 1e-9);
  EXPECT_NEAR(ground.elevation(run + 20.0, -30.0), crest - scene.slope_length * 0.5, 1e-9);
  EXPECT_NEAR(ground.slope(50.0, 0.0).x(), -tan_deg(30.0), 1e-12);
  EXPECT_NEAR(ground.slope(50.0, 0.0).y(), 0.0, 1e-12);
  // The whole flat runout zone and the side margins are inside the DEM.
  const double half_width = 0.5 * (scene.sources - 1) * scene.source_spacing + scene.side_margin;
  EXPECT_TRUE(ground.contains(run + scene.runout_length - 1.0, half_width - 1.0));
  EXPECT_TRUE(ground.contains(-scene.crest_length + 1.0, -half_width + 1.0));
  EXPECT_FALSE(ground.contains(run + scene.runout_length + scene.cell_size + 1.0, 0.0));
}

TEST(CalibrationGround, SourcesFormOneRowAcrossTheSlopeBelowTheCrest) {
  CalibrationScene scene;
  const auto sources = calibration_sources(scene);
  ASSERT_EQ(static_cast<int>(sources.size()), scene.sources);
  EXPECT_DOUBLE_EQ(sources.front().x, scene.cell_size);
  EXPECT_DOUBLE_EQ(sources.front().y + sources.back().y, 0.0);  // centred on y = 0
  EXPECT_DOUBLE_EQ(sources[1].y - sources[0].y, scene.source_spacing);
}

TEST(CalibrationObjective, SumsSquaredRelativeErrorsOfRunoutAndWeightedJump) {
  CalibrationSettings settings;  // 1 m rock, jump weight 0.1
  const std::vector<SlopeOutcome> target = {{100.0, 2.0, 0.0}, {200.0, 0.5, 0.0}};
  EXPECT_DOUBLE_EQ(calibration_objective(target, target, settings), 0.0);
  const std::vector<SlopeOutcome> fast = {{110.0, 3.0, 0.0}, {150.0, 0.5, 0.0}};
  // 0.1^2 + 0.1 x 0.5^2 + 0.25^2 + 0 (jump below the 1 m floor: error against 1 m).
  EXPECT_NEAR(calibration_objective(target, fast, settings), 0.01 + 0.025 + 0.0625, 1e-12);
  const std::vector<SlopeOutcome> still = {{0.0, 0.5, 0.0}};
  const std::vector<SlopeOutcome> moved = {{0.5, 0.5, 0.0}};
  EXPECT_NEAR(calibration_objective(still, moved, settings), 0.25, 1e-12);  // runout floor: the 1 m diameter
}

TEST(Calibration, UnknownClassIsAnInputError) {
  EXPECT_THROW(calibrate_fast_mode(builtin_materials(), {4, 12}, CalibrationSettings{}, nullptr), InputError);
}

// Tables whose class 4 has the given fast-mode coefficients.
MaterialsTable with_talus_coefficients(double restitution_normal, double restitution_tangential) {
  MaterialsTable table = builtin_materials();
  for (LithologyClass& lithology : table.lithology) {
    if (lithology.code != 4) continue;
    lithology.restitution_normal = restitution_normal;
    lithology.restitution_tangential = restitution_tangential;
  }
  return table;
}

// The fast mode fitted against itself: the target comes from coefficients where the runout
// depends on both, the fit starts from the built-in talus (Rn 0.38, Rt 0.65), and must come
// back to the truth, up to the valley of the objective.
TEST(Calibration, FastModeFittedAgainstItselfRecoversItsCoefficients) {
  CalibrationSettings settings;
  settings.scene.sources = 8;
  settings.runs_per_source = 4;
  settings.fast_runs_per_source = 4;  // the same draws as the target: the objective is 0 at the truth
  settings.threads = 2;
  const auto target = reference_outcomes(with_talus_coefficients(0.55, 0.8), 4, FastBounce(settings.fast), settings, nullptr);
  const ClassCalibration fit = fit_fast_mode(builtin_materials(), 4, target, settings, nullptr);
  // Tolerances: the objective has a narrow valley along which more Rn and less Rt give the
  // same runouts. Since fast mode rolls (Azzoni's rolling resistance, whose energy in rotation
  // caps Rt near 0.85 for a sphere without spin), the valley reaches far in Rn: the search stops
  // where the runouts match, not at the truth. Measured: Rn 0.2825, Rt 0.8675, objective 0.0058,
  // slope medians 1.009 and 1.039 of the target's. The coefficient pair is therefore checked only
  // in Rt; the runouts are the calibration's promise.
  EXPECT_TRUE(fit.fitted);
  EXPECT_NEAR(fit.restitution_tangential, 0.8, 0.1);
  EXPECT_LT(fit.objective_after, 0.01);
  EXPECT_GT(fit.objective_before, 0.1);  // the built-in coefficients stop rocks at the foot
  EXPECT_GT(fit.evaluations, 81);        // the 9 x 9 grid, then the refinement
  for (const SlopeComparison& slope : fit.slopes) {
    EXPECT_NEAR(slope.fast_after.median_runout / slope.full.median_runout, 1.0, 0.08);
  }
}

// Class 0 (swamp: friction 0.95 > tan 40 deg, no rebound) holds rocks released on both slopes:
// the slopes say nothing about its restitutions, which are kept.
TEST(Calibration, ClassWhoseRocksDoNotMoveKeepsItsCoefficients) {
  const MaterialsTable table = builtin_materials();
  CalibrationSettings settings;
  settings.threads = 2;
  const auto target = reference_outcomes(table, 0, FastBounce(settings.fast), settings, nullptr);
  for (const SlopeOutcome& slope : target) EXPECT_LT(slope.median_runout, settings.min_runout);
  const ClassCalibration fit = fit_fast_mode(table, 0, target, settings, nullptr);
  EXPECT_FALSE(fit.fitted);
  EXPECT_EQ(fit.evaluations, 0);
  EXPECT_EQ(fit.restitution_normal, table.find_lithology(0)->restitution_normal);
  EXPECT_EQ(fit.restitution_tangential, table.find_lithology(0)->restitution_tangential);
}

}  // namespace
}  // namespace talus
