// Same seed, same inputs: bit-identical layers at 1 and 2 threads (issue 5; docs/mudflow.md
// "Determinism"), for a uniform run that entrains (its 720 particles are enough for the particle
// loops to run in parallel) and for an adaptive one, each over the first 4 s of the chute's flow
// (down the erodible bed), for loops that switch between one and two threads, and for the
// interleaved order of evaluation (evaluation_order.hpp), which must give the two passes' layers.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>

#include <gtest/gtest.h>

#include "mudflow_scenes.hpp"

namespace talus {
namespace {

// True when both grids hold the same bits.
bool same_bits(const Grid<float>& a, const Grid<float>& b) {
  return a.size() == b.size() && std::memcmp(a.values().data(), b.values().data(), a.size() * sizeof(float)) == 0;
}

MudflowSettings first_seconds(bool adaptive, int threads) {
  MudflowSettings s = mudflow_scenes::Chute::settings(adaptive, threads);
  s.duration = 4.0;
  s.parallel_particles = 1;     // every per-particle loop in parallel, however short,
  s.parallel_check_period = 0;  // and never on one thread because a trial found that faster
  return s;
}

void expect_identical(const MudflowResult& one, const MudflowResult& two) {
  EXPECT_TRUE(same_bits(one.layers.flow_depth_max, two.layers.flow_depth_max));
  EXPECT_TRUE(same_bits(one.layers.velocity_max, two.layers.velocity_max));
  EXPECT_TRUE(same_bits(one.layers.pressure_max, two.layers.pressure_max));
  EXPECT_TRUE(same_bits(one.layers.deposit_depth, two.layers.deposit_depth));
  EXPECT_TRUE(same_bits(one.layers.arrival_time, two.layers.arrival_time));
  ASSERT_EQ(one.layers.erosion_depth.has_value(), two.layers.erosion_depth.has_value());
  if (one.layers.erosion_depth) {
    EXPECT_TRUE(same_bits(*one.layers.erosion_depth, *two.layers.erosion_depth));
  }
  EXPECT_EQ(one.particle_steps, two.particle_steps);
  EXPECT_EQ(one.final_particles, two.final_particles);
  EXPECT_EQ(one.simulated_time, two.simulated_time);
  EXPECT_EQ(one.threads, 1);
  EXPECT_EQ(two.threads, 2);
}

TEST(MudflowThreadDeterminism, UniformRunWithEntrainment) {
  const mudflow_scenes::Chute chute;
  const MudflowResult one = run_mudflow(chute.ground_model, chute.release_set, &chute.erodible,
                                        first_seconds(false, 1), nullptr);
  const MudflowResult two = run_mudflow(chute.ground_model, chute.release_set, &chute.erodible,
                                        first_seconds(false, 2), nullptr);
  EXPECT_GT(one.entrained_volume, 0.0);
  expect_identical(one, two);
}

TEST(MudflowThreadDeterminism, AdaptiveRun) {
  const mudflow_scenes::Chute chute;
  const MudflowResult one = run_mudflow(chute.ground_model, chute.release_set, &chute.erodible,
                                        first_seconds(true, 1), nullptr);
  const MudflowResult two = run_mudflow(chute.ground_model, chute.release_set, &chute.erodible,
                                        first_seconds(true, 2), nullptr);
  EXPECT_GT(one.splits, 0u);
  EXPECT_GT(one.entrained_volume, 0.0);
  expect_identical(one, two);
}

// A bowl that gathers a thin ring of mud into a pool several times as deep as released: the
// paraboloid z = 0.01 r^2 (m), 80 m x 80 m of 1 m cells, a ring of 1 m between r = 15 and 30 m,
// Coulomb friction tan(5 deg), 1 m particles, the first 15 s.
struct Bowl {
  GridSpec spec = mudflow_scenes::grid(80, 80, 1.0, -40.0, 40.0);
  GroundModel ground_model = mudflow_scenes::ground(spec, [](double x, double y) { return 0.01 * (x * x + y * y); });
  ReleaseSet release_set = mudflow_scenes::release(spec, [](double x, double y) {
    const double r = std::hypot(x, y);
    return (r > 15.0 && r < 30.0) ? 1.0 : 0.0;
  });

  MudflowResult run(double crowded_merge, int threads) const {
    MudflowSettings s = first_seconds(true, threads);
    s.duration = 15.0;
    s.particle_size = 1.0;
    s.crowded_merge = crowded_merge;
    s.rheology.rheology = Rheology::coulomb;
    s.rheology.friction = std::tan(5.0 * std::numbers::pi / 180.0);
    s.release_thickness = ReleaseThickness::vertical;
    return run_mudflow(ground_model, release_set, nullptr, s, nullptr);
  }
};

// Crowded fusion (docs/mudflow.md section 8) in the pool of the bowl: it merges more than the calm
// fusion alone (measured 378 against 348; with its smoothing floor and split rule but no crowded
// merges, 310) and makes at least 10% fewer particle-steps (measured 17%), fusion and fission
// conserve mass, and the layers stay the same at 1 and 2 threads.
TEST(MudflowThreadDeterminism, AdaptiveRunWithCrowdedFusion) {
  const Bowl bowl;
  const MudflowResult calm = bowl.run(0.0, 1);
  const MudflowResult one = bowl.run(1.5, 1);
  const MudflowResult two = bowl.run(1.5, 2);
  std::printf("bowl, first 15 s: %zu merges and %zu particle-steps with crowded fusion, %zu and %zu without\n",
              one.merges, one.particle_steps, calm.merges, calm.particle_steps);
  EXPECT_GT(one.merges, calm.merges);
  EXPECT_LT(static_cast<double>(one.particle_steps), 0.9 * static_cast<double>(calm.particle_steps));
  EXPECT_LE(one.adaptivity_mass_change, 1e-15);
  expect_identical(one, two);
}

// The timed trials of one thread against two (parallel_loop_choice.hpp) switch the loops between
// one and two threads from one coarse step to the next: the layers stay those of one thread. A
// period of 3 coarse steps makes the 8 coarse steps switch several times.
TEST(MudflowThreadDeterminism, SwitchingBetweenOneAndTwoThreadsChangesNothing) {
  const mudflow_scenes::Chute chute;
  const MudflowResult one = run_mudflow(chute.ground_model, chute.release_set, &chute.erodible,
                                        first_seconds(true, 1), nullptr);
  MudflowSettings switching = first_seconds(true, 2);
  switching.parallel_check_period = 3;
  const MudflowResult two = run_mudflow(chute.ground_model, chute.release_set, &chute.erodible, switching, nullptr);
  expect_identical(one, two);
}

// Every substep evaluated in the interleaved order (a thread's forces right after the densities
// they read), on one and on two threads, against the two passes: the same layers, adaptive and
// uniform. The chute's lists are far shorter than the default threshold, so it is set to 1.
TEST(MudflowThreadDeterminism, InterleavedEvaluationGivesTheTwoPassesLayers) {
  const mudflow_scenes::Chute chute;
  for (const bool adaptive : {false, true}) {
    SCOPED_TRACE(adaptive ? "adaptive" : "uniform");
    MudflowSettings two_passes = first_seconds(adaptive, 1);
    two_passes.interleaved_particles = 1 << 30;
    const MudflowResult reference =
        run_mudflow(chute.ground_model, chute.release_set, &chute.erodible, two_passes, nullptr);
    for (const int threads : {1, 2}) {
      MudflowSettings interleaved = first_seconds(adaptive, threads);
      interleaved.interleaved_particles = 1;
      const MudflowResult result =
          run_mudflow(chute.ground_model, chute.release_set, &chute.erodible, interleaved, nullptr);
      EXPECT_TRUE(same_bits(reference.layers.flow_depth_max, result.layers.flow_depth_max)) << threads;
      EXPECT_TRUE(same_bits(reference.layers.velocity_max, result.layers.velocity_max)) << threads;
      EXPECT_TRUE(same_bits(reference.layers.pressure_max, result.layers.pressure_max)) << threads;
      EXPECT_TRUE(same_bits(reference.layers.deposit_depth, result.layers.deposit_depth)) << threads;
      EXPECT_TRUE(same_bits(reference.layers.arrival_time, result.layers.arrival_time)) << threads;
      EXPECT_EQ(reference.particle_steps, result.particle_steps) << threads;
    }
  }
}

}  // namespace
}  // namespace talus
