// A release feature's conditions in a run (issue 16): the nominal rock and start velocity they
// give, and run_rockfall following them: a source whose conditions repeat the run's values gives
// bit-identical layers to one without conditions, and a thrown or lifted rock changes them.
#include "talus/rockfall/release_rock.hpp"

#include <algorithm>
#include <cstring>

#include <gtest/gtest.h>

#include "../../validation/synthetic_ground.hpp"
#include "talus/rockfall/fast_bounce.hpp"
#include "talus/rockfall/monte_carlo.hpp"

namespace talus {
namespace {

TEST(ReleaseRock, EmptyConditionsKeepTheRunsRockAtRest) {
  Rock run;
  run.shape = BlockShape::ellipsoid;
  run.axes = {2.0, 1.0, 0.5};
  run.density = 2500.0;
  const Rock rock = release_rock(run, {});
  EXPECT_EQ(rock.shape, run.shape);
  EXPECT_EQ(rock.axes, run.axes);
  EXPECT_EQ(rock.density, run.density);
  EXPECT_EQ(release_velocity({}), Eigen::Vector3d::Zero());
}

TEST(ReleaseRock, ConditionsSetShapeAxesDensityAndVelocity) {
  ReleaseConditions conditions;
  conditions.shape = BlockShape::box;
  conditions.axes = std::array<double, 3>{3.0, 2.0, 1.0};
  conditions.density = 3100.0;
  conditions.velocity = std::array<double, 3>{1.0, -2.0, 0.5};
  const Rock rock = release_rock(Rock{}, conditions);
  EXPECT_EQ(rock.shape, BlockShape::box);
  EXPECT_EQ(rock.axes, Eigen::Vector3d(3.0, 2.0, 1.0));
  EXPECT_EQ(rock.density, 3100.0);
  EXPECT_EQ(release_velocity(conditions), Eigen::Vector3d(1.0, -2.0, 0.5));
}

// A 150 x 150 m plane falling towards +x at 30 %, two point sources near its top.
class ReleaseConditionRuns : public ::testing::Test {
 protected:
  ReleaseConditionRuns()
      : ground_(testing_ground::make_ground(testing_ground::local_spec(30, 30, 5.0),
                                            [](double x, double) { return 200.0 - 0.3 * x; },
                                            testing_ground::fast_material(0.4, 0.7, 0.6))) {
    settings_.runs_per_source = 20;
    settings_.saved_trajectories = 0;
    settings_.threads = 2;
  }
  RockfallLayers run(const ReleaseConditions& conditions) const {
    const std::vector<ReleaseSource> sources{{20.0, -40.0, false, conditions}, {20.0, -100.0, false, conditions}};
    return run_rockfall(ground_, sources, FastBounce(), settings_, nullptr).statistics.layers();
  }
  static bool same(const Grid<float>& a, const Grid<float>& b) {
    return a.size() == b.size() && std::memcmp(a.values().data(), b.values().data(), a.size() * sizeof(float)) == 0;
  }
  GroundModel ground_;
  RockfallSettings settings_;
};

TEST_F(ReleaseConditionRuns, TheRunsOwnValuesGiveBitIdenticalLayers) {
  ReleaseConditions repeated;
  repeated.shape = settings_.rock.shape;
  repeated.axes = std::array<double, 3>{settings_.rock.axes.x(), settings_.rock.axes.y(), settings_.rock.axes.z()};
  repeated.density = settings_.rock.density;
  repeated.velocity = std::array<double, 3>{0.0, 0.0, 0.0};
  repeated.release_height = settings_.stochastic.release_height;
  const RockfallLayers plain = run({});
  const RockfallLayers same_values = run(repeated);
  EXPECT_TRUE(same(plain.passages, same_values.passages));
  EXPECT_TRUE(same(plain.energy_max, same_values.energy_max));
  EXPECT_TRUE(same(plain.jump_height_p95, same_values.jump_height_p95));
  EXPECT_TRUE(same(plain.energy_loss_friction, same_values.energy_loss_friction));
}

TEST_F(ReleaseConditionRuns, AThrownHeavierOrLiftedRockChangesTheLayers) {
  const RockfallLayers plain = run({});
  ReleaseConditions thrown;
  thrown.velocity = std::array<double, 3>{0.0, 8.0, 0.0};  // northwards, across the slope
  EXPECT_FALSE(same(plain.passages, run(thrown).passages));
  ReleaseConditions heavier;
  heavier.axes = std::array<double, 3>{2.0, 2.0, 2.0};
  heavier.density = 3000.0;
  const RockfallLayers big = run(heavier);
  EXPECT_GT(*std::max_element(big.energy_max.values().begin(), big.energy_max.values().end()),
            *std::max_element(plain.energy_max.values().begin(), plain.energy_max.values().end()));
  ReleaseConditions lifted;
  lifted.release_height = 20.0;
  const RockfallLayers high = run(lifted);
  EXPECT_GT(*std::max_element(high.jump_height_p95.values().begin(), high.jump_height_p95.values().end()),
            *std::max_element(plain.jump_height_p95.values().begin(), plain.jump_height_p95.values().end()));
}

}  // namespace
}  // namespace talus
