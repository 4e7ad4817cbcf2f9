// Tests of run_rockfall's batches (monte_carlo.hpp, envelope_convergence.hpp): --runs auto gives
// each source min_runs x 2^k runs, stops a source when its maps have converged, is the same for
// any thread count, and run k of source s is the same trajectory whatever the number of runs, so
// an auto source that ends at N runs has the layers of a fixed run of N. The recovery
// (docs/rockfall-full.md, section 5): a run that fails numerically is drawn again from a fresh
// stream, and one that fails on every draw is recorded and adds nothing, for any thread count.
#include "talus/rockfall/monte_carlo.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <gtest/gtest.h>

#include "../../validation/synthetic_ground.hpp"
#include "talus/rockfall/fast_bounce.hpp"
#include "talus/rockfall/step_guard.hpp"

namespace talus {
namespace {

// A 100 m slope falling towards +x at 80 % onto a flat floor (200 x 150 m in all), with 0.3 m of
// noise, three point sources near its top.
class MonteCarloBatches : public ::testing::Test {
 protected:
  MonteCarloBatches()
      : ground_(testing_ground::make_ground(testing_ground::local_spec(40, 30, 5.0),
                                            [](double x, double) { return 200.0 - 0.8 * std::min(x, 100.0); },
                                            testing_ground::fast_material(0.3, 0.6, 0.35, 0.0, 0.3))),
        sources_{{15.0, -40.0, false, {}}, {15.0, -75.0, false, {}}, {15.0, -110.0, false, {}}} {
    settings_.saved_trajectories = 0;
    settings_.threads = 2;
    settings_.convergence = {0.1, 8, 512};
  }
  RockfallResult run(const RockfallSettings& settings) const {
    return run_rockfall(ground_, sources_, FastBounce(), settings, nullptr);
  }
  RockfallSettings automatic() const {
    RockfallSettings s = settings_;
    s.auto_runs = true;
    return s;
  }
  static bool same(const Grid<float>& a, const Grid<float>& b) {
    return a.size() == b.size() && std::memcmp(a.values().data(), b.values().data(), a.size() * sizeof(float)) == 0;
  }
  static void expect_same_layers(const RockfallLayers& a, const RockfallLayers& b) {
    EXPECT_TRUE(same(a.passages, b.passages));
    EXPECT_TRUE(same(a.reach_probability, b.reach_probability));
    EXPECT_TRUE(same(a.energy_max, b.energy_max));
    EXPECT_TRUE(same(a.energy_p95, b.energy_p95));
    EXPECT_TRUE(same(a.deposits, b.deposits));
    EXPECT_TRUE(same(a.energy_loss_friction, b.energy_loss_friction));
  }
  GroundModel ground_;
  std::vector<ReleaseSource> sources_;
  RockfallSettings settings_;
};

TEST_F(MonteCarloBatches, AutoGivesEachSourceADoublingOfTheMinimumAndConverges) {
  const RockfallResult result = run(automatic());
  ASSERT_EQ(result.runs_by_source.size(), 3u);
  std::uint64_t total = 0;
  for (const std::uint64_t n : result.runs_by_source) {
    EXPECT_GE(n, 8u);
    EXPECT_LE(n, 512u);
    EXPECT_TRUE(n % 8 == 0 && ((n / 8) & (n / 8 - 1)) == 0) << n << " is not 8 x 2^k";
    total += n;
  }
  EXPECT_EQ(result.trajectories, total);
  EXPECT_EQ(result.runouts.size(), total);
  ASSERT_TRUE(result.convergence.has_value());
  const ConvergenceReport& c = *result.convergence;
  EXPECT_EQ(c.sources, 3u);
  EXPECT_EQ(c.run_limit, 512u);
  // Here every source converges before the limit, each after its own number of runs.
  EXPECT_EQ(c.sources_converged, 3u);
  EXPECT_EQ(c.sources_at_limit, 0u);
  EXPECT_NE(*std::min_element(result.runs_by_source.begin(), result.runs_by_source.end()),
            *std::max_element(result.runs_by_source.begin(), result.runs_by_source.end()));
  // Every source within the tolerance bounds the whole map within it (triangle inequality).
  EXPECT_TRUE(c.converged);
  EXPECT_LT(c.change.reach_change, 0.1);
  EXPECT_LT(c.change.energy_change, 0.1);
  EXPECT_GT(c.change.reached_after, 0u);
  EXPECT_GE(c.change.reached_after, c.change.reached_before);
}

TEST_F(MonteCarloBatches, AutoIsTheSameForAnyThreadCount) {
  RockfallSettings one = automatic(), three = automatic();
  one.threads = 1;
  three.threads = 3;
  const RockfallResult a = run(one), b = run(three);
  EXPECT_EQ(a.runs_by_source, b.runs_by_source);
  expect_same_layers(a.statistics.layers(), b.statistics.layers());
  EXPECT_EQ(a.runouts, b.runouts);
  ASSERT_TRUE(a.convergence && b.convergence);
  EXPECT_EQ(a.convergence->change.reach_change, b.convergence->change.reach_change);
  EXPECT_EQ(a.convergence->change.energy_change, b.convergence->change.energy_change);
}

TEST_F(MonteCarloBatches, AnAutoSourceThatEndsAtNRunsHasTheLayersOfNFixedRuns) {
  const RockfallResult whole = run(automatic());
  for (std::uint64_t s = 0; s < sources_.size(); ++s) {
    RockfallSettings auto_alone = automatic(), fixed_alone = settings_;
    auto_alone.only_source = fixed_alone.only_source = s;
    fixed_alone.runs_per_source = whole.runs_by_source[s];
    const RockfallResult a = run(auto_alone), f = run(fixed_alone);
    // The source alone decides its batches, so alone it gets as many runs as in the whole run.
    EXPECT_EQ(a.runs_by_source[s], whole.runs_by_source[s]) << "source " << s;
    expect_same_layers(a.statistics.layers(), f.statistics.layers());
    EXPECT_EQ(a.runouts, f.runouts);
  }
}

TEST_F(MonteCarloBatches, AFixedRunIsTestedHalfAgainstAll) {
  RockfallSettings few = settings_, many = settings_;
  few.runs_per_source = 4;
  many.runs_per_source = 128;
  const RockfallResult a = run(few), b = run(many);
  ASSERT_TRUE(a.convergence && b.convergence);
  EXPECT_EQ(a.runs_by_source, (std::vector<std::uint64_t>{4, 4, 4}));
  EXPECT_EQ(a.convergence->run_limit, 0u);
  EXPECT_GT(a.convergence->change.reach_change, b.convergence->change.reach_change);
  EXPECT_GT(a.convergence->change.energy_change, b.convergence->change.energy_change);
  EXPECT_FALSE(a.convergence->converged);
  EXPECT_GT(a.convergence->runs_suggested, 4u);
}

TEST_F(MonteCarloBatches, OneRunPerSourceIsNotTested) {
  RockfallSettings s = automatic();
  s.only_run = 5;
  const RockfallResult result = run(s);
  EXPECT_FALSE(result.convergence.has_value());
  EXPECT_EQ(result.trajectories, 3u);
  EXPECT_EQ(result.runs_by_source, (std::vector<std::uint64_t>{1, 1, 1}));
}

// Fast bounce, except that a draw `fails` decides fails numerically at its stop, after it has
// reported its whole path: what the recorder got must be forgotten.
class FailingModel final : public TrajectoryModel {
 public:
  using Rule = bool (*)(const Rock&, const RigidBodyState&);
  explicit FailingModel(Rule fails) : fails_(fails) {}
  StopReason run(const PerturbedGround& ground, const Rock& rock, RigidBodyState start,
                 TrajectoryObserver& observer) const override {
    if (!fails_(rock, start)) return FastBounce().run(ground, rock, start, observer);
    FailAtStop failing(observer);
    return FastBounce().run(ground, rock, start, failing);
  }

 private:
  class FailAtStop final : public TrajectoryObserver {
   public:
    explicit FailAtStop(TrajectoryObserver& to) : to_(to) {}
    void on_sample(const TrajectorySample& sample) override { to_.on_sample(sample); }
    void on_energy_loss(double x, double y, double friction, double deformation) override {
      to_.on_energy_loss(x, y, friction, deformation);
    }
    void on_stop(const TrajectorySample& last, StopReason) override {
      throw StepFailure("test failure", last.time, last.position, 1e-9, "the test's failure");
    }

   private:
    TrajectoryObserver& to_;
  };
  Rule fails_;
};

class MonteCarloRecovery : public MonteCarloBatches {
 protected:
  RockfallResult run_with(const FailingModel& model, const RockfallSettings& settings) const {
    return run_rockfall(ground_, sources_, model, settings, nullptr);
  }
};

// Source 1 (y = -75 m) fails on every draw: its runs are recorded with the failure's reason, time
// and place after settings.redraws fresh draws, and the run goes on. The layers are exactly those
// of sources 0 and 2 alone, whose runs draw the same numbers as in the whole run.
TEST_F(MonteCarloRecovery, ARunThatFailsOnEveryDrawIsRecordedAndAddsNothing) {
  const FailingModel model([](const Rock&, const RigidBodyState& start) { return std::abs(start.position.y() + 75.0) < 10.0; });
  RockfallSettings settings = settings_;
  settings.runs_per_source = 6;
  const RockfallResult result = run_with(model, settings);
  ASSERT_EQ(result.failures.size(), 6u);
  for (std::uint64_t k = 0; k < 6; ++k) {
    const FailedTrajectory& f = result.failures[k];
    EXPECT_EQ(f.source, 1u);
    EXPECT_EQ(f.run, k);
    EXPECT_EQ(f.reason, "the test's failure");
    EXPECT_GT(f.time, 0.0);
    EXPECT_GT(f.position.x(), 15.0);  // where it stopped, down the slope
  }
  EXPECT_EQ(result.troubled, 6u);
  EXPECT_EQ(result.redrawn, 6u);  // each drawn again, settings.redraws = 2 times
  EXPECT_EQ(result.trajectories, 12u);
  EXPECT_EQ(result.statistics.rocks(), 12u);
  EXPECT_EQ(result.runouts.size(), 12u);
  EXPECT_EQ(result.runs_by_source, (std::vector<std::uint64_t>{6, 6, 6}));

  RockfallSettings first = settings, last = settings;
  first.only_source = 0;
  last.only_source = 2;
  RockfallResult alone = run(first);
  alone.statistics.merge(run(last).statistics);
  expect_same_layers(result.statistics.layers(), alone.statistics.layers());
}

// Draws whose rock came out larger than the nominal 1 m fail (about half): without redraws they
// are the failures; with two, the runs drawn again from fresh streams mostly pass and a few fail on
// all three draws. Failures, layers and runouts are the same at 1 and 3 threads.
TEST_F(MonteCarloRecovery, FreshDrawsMendMostFailuresTheSameWayForAnyThreadCount) {
  const FailingModel model([](const Rock& rock, const RigidBodyState&) { return rock.axes.x() > 1.0; });
  RockfallSettings settings = settings_;
  settings.runs_per_source = 16;
  settings.redraws = 0;
  const RockfallResult without = run_with(model, settings);
  EXPECT_EQ(without.failures.size(), without.troubled);
  EXPECT_EQ(without.redrawn, 0u);
  EXPECT_GT(without.failures.size(), 10u);
  EXPECT_EQ(without.trajectories + without.failures.size(), 48u);

  settings.redraws = 2;
  std::vector<RockfallResult> results;
  for (const int threads : {1, 3}) {
    settings.threads = threads;
    results.push_back(run_with(model, settings));
  }
  const RockfallResult& with = results.front();
  std::printf("failed without redraws %zu of 48, with two %zu\n", without.failures.size(), with.failures.size());
  EXPECT_EQ(with.troubled, without.troubled);  // the first draws are the same
  EXPECT_EQ(with.redrawn, without.troubled);
  EXPECT_LT(with.failures.size(), without.failures.size() / 2);
  EXPECT_EQ(with.trajectories + with.failures.size(), 48u);
  EXPECT_EQ(with.statistics.rocks(), with.trajectories);
  const RockfallResult& other = results.back();
  ASSERT_EQ(with.failures.size(), other.failures.size());
  for (std::size_t k = 0; k < with.failures.size(); ++k) {
    EXPECT_EQ(with.failures[k].source, other.failures[k].source);
    EXPECT_EQ(with.failures[k].run, other.failures[k].run);
    EXPECT_EQ(with.failures[k].time, other.failures[k].time);
  }
  expect_same_layers(with.statistics.layers(), other.statistics.layers());
  EXPECT_EQ(with.runouts, other.runouts);
}

}  // namespace
}  // namespace talus
