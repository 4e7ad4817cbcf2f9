// Where the full model's explicit integration fails (issue 4, Deliver 5): on the stiffest soil
// class, a contact step far above the stability limit (omega dt = 2 pi time_step_factor > 2)
// multiplies the rock's energy at every step. Without the guard the run blows up; with it, the
// guard halves the failing steps and the same run stays within its initial energy. With no
// halving allowed, the recovery (docs/rockfall-full.md, section 5) restarts the rock from its last
// sound state with shorter steps, or, without restarts, the run throws StepFailure.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "full_model_scenes.hpp"
#include "talus/core/errors.hpp"
#include "talus/rockfall/full_model.hpp"
#include "talus/rockfall/implicit_shape.hpp"
#include "talus/rockfall/step_guard.hpp"

namespace talus {
namespace {

using testing_ground::Recorder;

constexpr double kG = 9.81;

struct StiffDrop {
  // The stiffest built-in class (talus, k3 = 1.9e8 Pa/m).
  GroundModel model = full_model_scenes::inclined_plane(20, 20, 5.0, 50.0, 0.2, full_model_scenes::talus_soil());
  PerturbedGround ground{model, nullptr};
  Rock rock = full_model_scenes::sphere(1.0);
  RigidBodyState start = full_model_scenes::released(ground, 30.0, -50.0, 2.0);

  FullModelParameters parameters(bool guard) const {
    FullModelParameters p;
    p.guard = guard;
    p.time_step_factor = 1.0;   // omega dt = 2 pi: far beyond velocity Verlet's limit of 2
    p.approach_fraction = 4.0;  // no approach rule,
    p.max_flight_step = 0.1;    // nor flight step, to shorten the contact steps instead
    p.max_time = 10.0;
    p.drag_coefficient = 0.0;
    return p;
  }
  double mass(const FullModelParameters& p) const {
    return integrate_mass(ImplicitShape(rock, p.surface_samples), rock.density, p.mass_resolution).mass;
  }
  // Largest kinetic + potential energy (J) of the samples, from the release's.
  double largest_gain(const Recorder& recorder, double m) const {
    double largest = 0.0;
    for (const TrajectorySample& sample : recorder.samples) {
      largest = std::max(largest, sample.kinetic_energy + m * kG * (sample.position.z() - start.position.z()));
    }
    return largest;
  }
};

TEST(FullModelStability, WithoutTheGuardATooLongContactStepBlowsUp) {
  const StiffDrop scene;
  const FullModelParameters parameters = scene.parameters(false);
  Recorder recorder;
  bool failed = false;
  try {
    FullModel(parameters).run(scene.ground, scene.rock, scene.start, recorder);
  } catch (const NumericalFailure& failure) {
    failed = true;
    std::printf("unguarded: %s\n", failure.what());
  }
  const double m = scene.mass(parameters);
  const double drop = m * kG * 2.0;  // J: the release's energy above the ground
  const double gain = scene.largest_gain(recorder, m);
  std::printf("unguarded: energy gained %.3g J, %.3g times the drop's %.3g J\n", gain, gain / drop, drop);
  // Blown up: a non-finite state (NumericalFailure) or energy grown a hundredfold.
  EXPECT_TRUE(failed || !(gain < 100.0 * drop));
}

TEST(FullModelStability, WithTheGuardTheSameRunStaysStable) {
  const StiffDrop scene;
  const FullModelParameters parameters = scene.parameters(true);
  Recorder recorder;
  EnergyBalance balance;
  ASSERT_NO_THROW(FullModel(parameters).run(scene.ground, scene.rock, scene.start, recorder, balance));
  const double m = scene.mass(parameters);
  const double drop = m * kG * 2.0;
  const double gain = scene.largest_gain(recorder, m);
  const double final_gain = balance.kinetic + balance.elastic + m * kG * (recorder.final_sample.position.z() -
                                                                         scene.start.position.z());
  std::printf("guarded: largest energy gained %.3g J, at the end %.3g J (drop %.3g J)\n", gain, final_gain, drop);
  // Stable: never more energy than at the release (1% of the drop's for the guard's tolerance).
  EXPECT_LT(gain, 0.01 * drop);
  EXPECT_LT(final_gain, 0.01 * drop);
  EXPECT_GT(recorder.final_sample.position.x(), scene.start.position.x() + 1.0);  // it went down the slope
}

// docs/rockfall-full.md, section 5, "Recovery": the guard may not halve (max_retries 0), so the
// first contact step of omega dt = 2 pi fails. Without restarts the run throws StepFailure with
// its reason, time and place; with them it restarts from the last sound state with contact steps
// a quarter as long (omega dt = pi / 2, stable), finishes, and reports one consistent trajectory:
// samples in time order, none from the withdrawn steps, and no energy gained.
TEST(FullModelRecovery, AFailedStepRestartsFromTheLastSoundStateWithShorterSteps) {
  const StiffDrop scene;
  FullModelParameters parameters = scene.parameters(true);
  parameters.max_retries = 0;
  parameters.restarts = 0;
  Recorder failing;
  try {
    FullModel(parameters).run(scene.ground, scene.rock, scene.start, failing);
    ADD_FAILURE() << "no step failed";
  } catch (const StepFailure& failure) {
    std::printf("without restarts: %s\n", failure.what());
    EXPECT_EQ(failure.reason, "blow-up not recovered by smaller steps");
    EXPECT_GT(failure.time, 0.0);
    EXPECT_LT(failure.position.z(), scene.start.position.z());
  }
  EXPECT_EQ(failing.restarts, 0);

  parameters.restarts = 2;
  Recorder recorder;
  ASSERT_NO_THROW(FullModel(parameters).run(scene.ground, scene.rock, scene.start, recorder));
  std::printf("with restarts: %d, %zu samples, stopped at t = %.3g s\n", recorder.restarts, recorder.samples.size(),
              recorder.final_sample.time);
  EXPECT_GE(recorder.restarts, 1);
  EXPECT_LE(recorder.restarts, 2);
  EXPECT_EQ(recorder.stops, 1);
  for (std::size_t k = 1; k < recorder.samples.size(); ++k) {
    EXPECT_GE(recorder.samples[k].time, recorder.samples[k - 1].time) << "sample " << k;
  }
  const double m = scene.mass(parameters);
  const double drop = m * kG * 2.0;  // J
  EXPECT_LT(scene.largest_gain(recorder, m), 0.01 * drop);
  EXPECT_EQ(recorder.stop, StopReason::at_rest);
  EXPECT_GT(recorder.final_sample.position.x(), scene.start.position.x() + 0.5);  // down the slope, to rest
}

}  // namespace
}  // namespace talus
