// Tests of the full rock-ground model's run (paper 2.2, 3.1-3.3) beyond the physics of
// tests/validation/full_model_*: stop reasons, what the observer receives (samples, losses, the
// stop), and the numerical failure it reports when the guard cannot recover.
#include "talus/rockfall/full_model.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "../../validation/full_model_scenes.hpp"
#include "talus/core/errors.hpp"

namespace talus {
namespace {

using testing_ground::Recorder;

GroundModel plane(double gradient, const GroundMaterial& material) {
  return full_model_scenes::inclined_plane(30, 30, 5.0, 200.0, gradient, material);
}

TEST(FullModel, BoxPutOnAGentleSlopeComesToRest) {
  const GroundModel model = plane(0.1, full_model_scenes::talus_soil());  // 5.7 degrees, mu 0.4
  const PerturbedGround ground(model, nullptr);
  const Rock rock = full_model_scenes::block(BlockShape::box, {1.0, 0.8, 0.5});
  const double slope = std::atan(0.1);
  // Lying flat on the slope, 1 cm above it.
  RigidBodyState start = full_model_scenes::released(ground, 70.0, -70.0, 0.26 / std::cos(slope));
  start.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(slope, Eigen::Vector3d::UnitY()));
  Recorder recorder;
  const StopReason reason = FullModel().run(ground, rock, start, recorder);
  EXPECT_EQ(reason, StopReason::at_rest);
  EXPECT_EQ(recorder.stop, StopReason::at_rest);
  std::printf("at rest after %.2f s, %.1f mm from the release\n", recorder.final_sample.time,
              1e3 * (recorder.final_sample.position - start.position).head<2>().norm());
  EXPECT_LT(recorder.final_sample.time, 2.5);  // s: settles within a few stop_duration windows
  EXPECT_LT((recorder.final_sample.position - start.position).head<2>().norm(), 0.05);  // m: it settled, never slid
}

TEST(FullModel, SphereRollingOffTheGridLeavesTheDem) {
  const GroundModel model = plane(0.3, full_model_scenes::talus_soil());
  const PerturbedGround ground(model, nullptr);
  RigidBodyState start = full_model_scenes::released(ground, 130.0, -70.0, 0.6);
  start.velocity = {8.0, 0.0, 0.0};
  Recorder recorder;
  const StopReason reason = FullModel().run(ground, full_model_scenes::sphere(1.0), start, recorder);
  EXPECT_EQ(reason, StopReason::left_dem);
  EXPECT_EQ(recorder.stops, 1);
  // The last state reported is the last one on the DEM.
  EXPECT_TRUE(ground.contains(recorder.final_sample.position.x(), recorder.final_sample.position.y()));
  EXPECT_GT(recorder.final_sample.position.x(), 140.0);
}

TEST(FullModel, SphereRollingIntoAHoleStopsInTheNodataArea) {
  const GridSpec spec = testing_ground::local_spec(30, 30, 5.0);
  Grid<double> z(spec);
  for (int row = 0; row < 30; ++row) {
    for (int col = 0; col < 30; ++col) z.at(col, row) = (col >= 18 && col <= 22) ? spec.nodata : 200.0 - 1.5 * col;
  }
  const GroundModel model(std::move(z), Grid<GroundMaterial>(spec, full_model_scenes::talus_soil()));
  const PerturbedGround ground(model, nullptr);
  RigidBodyState start = full_model_scenes::released(ground, 70.0, -70.0, 0.6);
  start.velocity = {5.0, 0.0, 0.0};
  FullModelParameters pure_rolling;  // no rolling resistance: the sphere keeps rolling into the hole
  pure_rolling.rolling_resistance = 0.0;
  Recorder recorder;
  EXPECT_EQ(FullModel(pure_rolling).run(ground, full_model_scenes::sphere(1.0), start, recorder), StopReason::nodata_area);
}

TEST(FullModel, StopsAtMaxTime) {
  const GroundModel model = plane(0.0, full_model_scenes::talus_soil());
  const PerturbedGround ground(model, nullptr);
  FullModelParameters parameters;
  parameters.max_time = 0.75;
  Recorder recorder;
  const StopReason reason = FullModel(parameters).run(ground, full_model_scenes::sphere(1.0),
                                                      full_model_scenes::released(ground, 70.0, -70.0, 40.0), recorder);
  EXPECT_EQ(reason, StopReason::max_time);
  EXPECT_NEAR(recorder.final_sample.time, 0.75, 1e-12);
}

// Release sample, spacing, contact samples, final sample = the stop's, energies with the spin.
TEST(FullModel, ReportsReleaseSamplesEverySpacingContactsAndTheStop) {
  const GroundModel model = plane(0.5, full_model_scenes::talus_soil());
  const PerturbedGround ground(model, nullptr);
  FullModelParameters parameters;
  parameters.sample_spacing = 1.0;
  parameters.max_time = 6.0;
  parameters.rolling_resistance = 0.0;  // pure rolling, so the spin's share of the energy is 2/7
  RigidBodyState start = full_model_scenes::released(ground, 10.0, -70.0, 2.5);
  start.velocity = {6.0, 1.0, 0.0};
  Recorder recorder;
  FullModel(parameters).run(ground, full_model_scenes::sphere(1.0), start, recorder);
  ASSERT_GE(recorder.samples.size(), 10u);
  EXPECT_EQ(recorder.samples.front().time, 0.0);
  EXPECT_EQ(recorder.samples.front().position, start.position);
  EXPECT_NEAR(recorder.samples.front().jump_height, 2.5, 1e-9);
  int touchdowns = 0;  // samples within 5 cm of touching the ground after a flight
  for (std::size_t i = 1; i < recorder.samples.size(); ++i) {
    const TrajectorySample& a = recorder.samples[i - 1];
    const TrajectorySample& b = recorder.samples[i];
    // Path between samples: within the spacing (the straight segment is shorter than the path).
    EXPECT_LE((b.position - a.position).norm(), parameters.sample_spacing * (1.0 + 1e-9));
    EXPECT_GE(b.time, a.time);
    if (a.jump_height > 0.6 && b.jump_height < 0.55) ++touchdowns;
  }
  EXPECT_GE(touchdowns, 1);  // the landing is sampled where the contact starts
  EXPECT_EQ(recorder.stops, 1);
  EXPECT_EQ(recorder.final_sample.time, recorder.samples.back().time);
  EXPECT_EQ(recorder.final_sample.position, recorder.samples.back().position);
  // A rolling sphere: kinetic energy above its translation's (the spin counts).
  const TrajectorySample& last = recorder.final_sample;
  const double translation = 0.5 * full_model_scenes::sphere(1.0).mass() * last.velocity.squaredNorm();
  EXPECT_GT(last.kinetic_energy, 1.2 * translation);
}

// Every reported loss is an energy lost (>= 0), reported where the rock is.
TEST(FullModel, LossesArePositiveAndUnderTheRock) {
  const GroundModel model = plane(0.4, full_model_scenes::talus_soil(0.4, 0.01));
  const PerturbedGround ground(model, nullptr);
  FullModelParameters parameters;
  parameters.max_time = 4.0;
  RigidBodyState start = full_model_scenes::released(ground, 10.0, -70.0, 1.5);
  start.velocity = {4.0, 0.0, 0.0};
  Recorder recorder;
  FullModel(parameters).run(ground, full_model_scenes::block(BlockShape::ellipsoid, {1.2, 0.9, 0.6}), start, recorder);
  ASSERT_GT(recorder.losses.size(), 10u);
  Eigen::AlignedBox2d path;  // of the centre, widened by the bounding radius (0.6 m)
  for (const TrajectorySample& sample : recorder.samples) path.extend(sample.position.head<2>());
  path.extend(path.min() - Eigen::Vector2d::Constant(0.6));
  path.extend(path.max() + Eigen::Vector2d::Constant(0.6));
  for (const testing_ground::RecordedLoss& loss : recorder.losses) {
    EXPECT_GE(loss.friction, 0.0);
    EXPECT_GE(loss.deformation, 0.0);
    EXPECT_TRUE(path.contains(Eigen::Vector2d(loss.x, loss.y))) << loss.x << ", " << loss.y;
  }
  EXPECT_GT(recorder.friction_loss(), 0.0);
  EXPECT_GT(recorder.deformation_loss(), 0.0);
}

// With no halving and no restart allowed, a step far beyond the stability limit fails with a
// message that names the time, the centre and the step.
TEST(FullModel, UnrecoverableBlowUpThrowsNumericalFailure) {
  const GroundModel model = plane(0.0, full_model_scenes::talus_soil());
  const PerturbedGround ground(model, nullptr);
  FullModelParameters parameters;
  parameters.time_step_factor = 1.0;
  parameters.approach_fraction = 4.0;
  parameters.max_flight_step = 0.1;
  parameters.max_retries = 0;
  parameters.restarts = 0;
  Recorder recorder;
  try {
    FullModel(parameters).run(ground, full_model_scenes::sphere(1.0),
                              full_model_scenes::released(ground, 70.0, -70.0, 2.0), recorder);
    FAIL() << "expected NumericalFailure";
  } catch (const NumericalFailure& failure) {
    const std::string message = failure.what();
    EXPECT_NE(message.find("t = "), std::string::npos) << message;
    EXPECT_NE(message.find("centre (70.000, -70.000"), std::string::npos) << message;
    EXPECT_NE(message.find("step"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace talus
