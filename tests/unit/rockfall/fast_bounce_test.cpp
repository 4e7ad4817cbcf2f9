// Tests of the fast bounce trajectory (paper 3.3, "Fast Bounce mode") beyond the closed forms of
// tests/validation: stop reasons, what the observer receives (samples, losses, the stop), energy
// bookkeeping, vegetation at impacts, non-spherical rocks, and the unperturbed ground.
#include "talus/rockfall/fast_bounce.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "../../validation/synthetic_ground.hpp"
#include "talus/core/errors.hpp"
#include "talus/ground/perlin_noise.hpp"

namespace talus {
namespace {

using testing_ground::Recorder;

constexpr double kG = 9.81;

Rock sphere(double diameter = 1.0) {
  Rock rock;
  rock.axes = Eigen::Vector3d::Constant(diameter);
  return rock;
}

// 30 x 30 cells of 5 m; a plane falling towards +x with the given gradient.
GroundModel plane(double gradient, const GroundMaterial& material) {
  return testing_ground::make_ground(testing_ground::local_spec(30, 30, 5.0),
                                     [gradient](double x, double) { return 200.0 - gradient * x; }, material);
}

RigidBodyState at(const PerturbedGround& ground, double x, double y, double above, const Eigen::Vector3d& v) {
  RigidBodyState start;
  start.position = {x, y, ground.height(x, y) + above};
  start.velocity = v;
  return start;
}

TEST(FastBounce, RockThrownOffTheGridLeavesTheDem) {
  const GroundModel model = plane(0.2, testing_ground::fast_material(0.5, 0.8, 0.5));
  const PerturbedGround ground(model, nullptr);
  Recorder recorder;
  const StopReason reason = FastBounce().run(ground, sphere(), at(ground, 120.0, -70.0, 3.0, {25.0, 0.0, 5.0}), recorder);
  EXPECT_EQ(reason, StopReason::left_dem);
  EXPECT_EQ(recorder.stop, StopReason::left_dem);
  EXPECT_EQ(recorder.stops, 1);
  EXPECT_TRUE(ground.contains(recorder.final_sample.position.x(), recorder.final_sample.position.y()));
}

TEST(FastBounce, RockRollingIntoAHoleStopsInTheNodataArea) {
  const GridSpec spec = testing_ground::local_spec(30, 30, 5.0);
  Grid<double> z(spec);
  for (int row = 0; row < 30; ++row) {
    for (int col = 0; col < 30; ++col) z.at(col, row) = (col >= 18 && col <= 22) ? spec.nodata : 200.0 - 1.0 * col * 5.0;
  }
  const GroundModel model(std::move(z), Grid<GroundMaterial>(spec, testing_ground::fast_material(0.3, 0.7, 0.3)));
  const PerturbedGround ground(model, nullptr);
  Recorder recorder;
  const StopReason reason = FastBounce().run(ground, sphere(), at(ground, 20.0, -70.0, 0.5, {2.0, 0.0, 0.0}), recorder);
  EXPECT_EQ(reason, StopReason::nodata_area);
}

TEST(FastBounce, StopsAtMaxTime) {
  const GroundModel model = plane(0.0, testing_ground::fast_material(0.5, 0.8, 0.5));
  const PerturbedGround ground(model, nullptr);
  FastBounceParameters parameters;
  parameters.max_time = 0.75;
  Recorder recorder;
  const StopReason reason =
      FastBounce(parameters).run(ground, sphere(), at(ground, 70.0, -70.0, 40.0, Eigen::Vector3d::Zero()), recorder);
  EXPECT_EQ(reason, StopReason::max_time);
  EXPECT_NEAR(recorder.final_sample.time, 0.75, 1e-12);
}

// Issue 18, item 4: steps that no longer advance the clock (here a 1e-13 m flight path between
// ground checks, below what the parameter's range allows, at 10 m/s: 1e-14 s per step, which
// would take 3e16 steps to reach max_time) end the trajectory with NumericalFailure, naming the
// stall, instead of spinning.
TEST(FastBounce, AStalledTrajectoryIsANumericalFailureNotAnEndlessLoop) {
  const GroundModel model = plane(0.5, testing_ground::fast_material(0.5, 0.8, 0.5));
  const PerturbedGround ground(model, nullptr);
  FastBounceParameters parameters;
  parameters.max_step_length = 1e-13;
  Recorder recorder;
  try {
    FastBounce(parameters).run(ground, sphere(), at(ground, 70.0, -70.0, 20.0, {10.0, 0.0, 0.0}), recorder);
    ADD_FAILURE() << "the stalled trajectory ended normally";
  } catch (const NumericalFailure& e) {
    EXPECT_NE(std::string(e.what()).find("the trajectory stalled (10000 steps in a row shorter than 1e-09 s)"),
              std::string::npos)
        << e.what();
  }
}

TEST(FastBounce, ReportsReleaseSamplesEverySpacingAndTheStop) {
  const GroundModel model = plane(0.7, testing_ground::fast_material(0.4, 0.7, 0.6));
  const PerturbedGround ground(model, nullptr);
  FastBounceParameters parameters;
  Recorder recorder;
  const RigidBodyState start = at(ground, 10.0, -70.0, 2.5, {6.0, 1.0, 0.0});
  FastBounce(parameters).run(ground, sphere(), start, recorder);
  ASSERT_GE(recorder.samples.size(), 3u);
  EXPECT_EQ(recorder.samples.front().time, 0.0);
  EXPECT_LT((recorder.samples.front().position - start.position).norm(), 1e-12);
  for (std::size_t i = 1; i < recorder.samples.size(); ++i) {
    const double gap = (recorder.samples[i].position - recorder.samples[i - 1].position).norm();
    EXPECT_LE(gap, parameters.sample_spacing * (1.0 + 1e-9));
    EXPECT_GE(recorder.samples[i].time, recorder.samples[i - 1].time);
    EXPECT_GE(recorder.samples[i].jump_height, 0.5 - 1e-9);  // the centre never below touching
  }
  EXPECT_EQ(recorder.stops, 1);
  EXPECT_EQ(recorder.final_sample.time, recorder.samples.back().time);
  EXPECT_EQ(recorder.final_sample.position, recorder.samples.back().position);
  // Energies count translation and rotation: at least the translation's.
  for (const TrajectorySample& s : recorder.samples) {
    EXPECT_GE(s.kinetic_energy, 0.5 * sphere().mass() * s.velocity.squaredNorm() * (1.0 - 1e-12));
  }
}

// No drag, no vegetation: the release's kinetic and potential energy ends up in the reported
// losses once the rock is at rest on a plane gentler than its friction.
TEST(FastBounce, LossesAccountForTheEnergyOnAPlane) {
  const GroundModel model = plane(0.25, testing_ground::fast_material(0.45, 0.75, 0.6));
  const PerturbedGround ground(model, nullptr);
  FastBounceParameters parameters;
  parameters.drag_coefficient = 0.0;
  Recorder recorder;
  const Rock rock = sphere();
  const RigidBodyState start = at(ground, 15.0, -70.0, 6.0, {7.0, 2.0, 3.0});
  ASSERT_EQ(FastBounce(parameters).run(ground, rock, start, recorder), StopReason::at_rest);
  const double m = rock.mass();
  const double given = 0.5 * m * start.velocity.squaredNorm() + m * kG * (start.position.z() - recorder.final_sample.position.z());
  const double lost = recorder.friction_loss() + recorder.deformation_loss();
  EXPECT_NEAR(lost / given, 1.0, 1e-3);
  EXPECT_GT(recorder.friction_loss(), 0.0);
  EXPECT_GT(recorder.deformation_loss(), 0.0);
}

TEST(FastBounce, VegetationSlowsAnImpactOverTheRocksDiameter) {
  const double c = 0.04, rn = 0.6;
  const GroundModel model = plane(0.0, testing_ground::fast_material(rn, 1.0, 0.5, c));
  const PerturbedGround ground(model, nullptr);
  FastBounceParameters parameters;
  parameters.drag_coefficient = 0.0;
  Recorder recorder;
  const Rock rock = sphere(2.0);
  FastBounce(parameters).run(ground, rock, at(ground, 70.0, -70.0, 1.0 + 5.0, Eigen::Vector3d::Zero()), recorder);
  // The first loss is the first impact: v = sqrt(2 g 5), kept speed rn v exp(-c d), d = 2 m.
  ASSERT_FALSE(recorder.losses.empty());
  const double m = rock.mass();
  const double v = std::sqrt(2.0 * kG * 5.0);
  const double restituted = 0.5 * m * rn * rn * v * v;
  EXPECT_NEAR(recorder.losses[0].deformation / (0.5 * m * v * v - restituted), 1.0, 1e-5);
  EXPECT_NEAR(recorder.losses[0].friction / (restituted * (1.0 - std::exp(-2.0 * c * 2.0))), 1.0, 1e-5);
  EXPECT_NEAR(recorder.losses[0].x, 70.0, 1e-9);
}

TEST(FastBounce, EllipsoidsAndBoxesComeToRestOnTheGround) {
  const GroundModel model = plane(0.3, testing_ground::fast_material(0.4, 0.7, 0.6));
  const PerturbedGround ground(model, nullptr);
  for (const BlockShape shape : {BlockShape::ellipsoid, BlockShape::box}) {
    Rock rock;
    rock.shape = shape;
    rock.axes = {1.6, 1.0, 0.6};
    RigidBodyState start = at(ground, 15.0, -70.0, 4.0, {5.0, 1.0, 0.0});
    start.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 1.0, 0.2).normalized()));
    start.angular_velocity = {0.0, 3.0, 1.0};
    Recorder recorder;
    EXPECT_EQ(FastBounce().run(ground, rock, start, recorder), StopReason::at_rest);
    for (const TrajectorySample& s : recorder.samples) {
      EXPECT_GE(s.jump_height, 0.3 - 1e-9);  // at least the smallest half axis above the ground
      EXPECT_LE(s.jump_height, std::max(4.0 + 0.8, s.jump_height));
    }
    EXPECT_GT((recorder.final_sample.position - start.position).head<2>().norm(), 3.0);
  }
}

// A noise object on a lithology without roughness changes nothing, bit for bit.
TEST(FastBounce, ZeroAmplitudeNoiseGivesTheUnperturbedTrajectory) {
  const GroundModel model = testing_ground::make_ground(
      testing_ground::local_spec(30, 30, 5.0), [](double x, double y) { return 200.0 - 0.4 * x + 3.0 * std::sin(0.05 * y); },
      testing_ground::fast_material(0.45, 0.7, 0.5, 0.01, 0.0));
  PerlinParameters noise_parameters;
  noise_parameters.amplitude = 1.0;
  const PerlinNoise noise(noise_parameters);
  const PerturbedGround bare(model, nullptr), noisy(model, &noise);
  Recorder a, b;
  FastBounce().run(bare, sphere(), at(bare, 12.0, -60.0, 2.0, {6.0, -2.0, 1.0}), a);
  FastBounce().run(noisy, sphere(), at(noisy, 12.0, -60.0, 2.0, {6.0, -2.0, 1.0}), b);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  ASSERT_GT(a.samples.size(), 10u);
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    EXPECT_EQ(a.samples[i].position, b.samples[i].position);
    EXPECT_EQ(a.samples[i].velocity, b.samples[i].velocity);
  }
  EXPECT_EQ(a.stop, b.stop);
}

TEST(FastBounce, ReleaseBelowTheGroundIsPutOnIt) {
  const GroundModel model = plane(0.1, testing_ground::fast_material(0.4, 0.7, 0.6));
  const PerturbedGround ground(model, nullptr);
  Recorder recorder;
  const StopReason reason = FastBounce().run(ground, sphere(), at(ground, 70.0, -70.0, -2.0, Eigen::Vector3d::Zero()), recorder);
  EXPECT_EQ(reason, StopReason::at_rest);
  EXPECT_NEAR(recorder.samples.front().jump_height, 0.5, 1e-12);
}

}  // namespace
}  // namespace talus
