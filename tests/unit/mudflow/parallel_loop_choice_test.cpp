// One thread or all for the mud flow's particle loops, chosen by timed trials
// (parallel_loop_choice.hpp): the sequence of choices for given timings.
#include "talus/mudflow/parallel_loop_choice.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace talus {
namespace {

// The way each of `costs.size()` coarse steps runs when the step run in parallel costs
// `parallel_cost` s per particle-step and one on one thread `one_thread_cost`, 1000
// particle-steps each.
std::vector<bool> choices(int period, double one_thread_cost, double parallel_cost, int steps) {
  ParallelLoopChoice choice(period);
  std::vector<bool> ways;
  for (int step = 0; step < steps; ++step) {
    ways.push_back(choice.parallel());
    choice.record(1000.0 * (choice.parallel() ? parallel_cost : one_thread_cost), 1000);
  }
  return ways;
}

TEST(ParallelLoopChoice, PeriodZeroAlwaysRunsInParallel) {
  EXPECT_EQ(choices(0, 1.0, 5.0, 6), std::vector<bool>(6, true));
}

TEST(ParallelLoopChoice, RunsInParallelWhenTheTrialsFindItFaster) {
  // Trials (one thread, then all), the rest of the first period of 4 in parallel; the same answer
  // doubles the next period to 8 and then to 16.
  const std::vector<bool> expected = {false, true, true, true,                                  // 4
                                      false, true, true, true, true, true, true, true,          // 8
                                      false, true, true, true, true, true, true, true, true, true,
                                      true, true, true, true, true, true};                      // 16
  EXPECT_EQ(choices(4, 2.0, 1.0, 28), expected);
}

TEST(ParallelLoopChoice, StaysOnOneThreadWhenTheTrialsFindItFaster) {
  const std::vector<bool> expected = {false, true, false, false, false, true, false, false, false, false, false, false};
  EXPECT_EQ(choices(4, 1.0, 2.5, 12), expected);
}

TEST(ParallelLoopChoice, ThePeriodGrowsToEightTimesTheFirstAndResetsWhenTheAnswerChanges) {
  ParallelLoopChoice choice(3);
  int trials = 0;
  int steps_since_trial = 0, longest_gap = 0;
  // 400 coarse steps where parallel is faster: trials at 0, 3, 9, 21, 45, 69, ...: gaps 3, 6, 12, 24, 24.
  for (int step = 0; step < 400; ++step) {
    if (!choice.parallel()) {
      ++trials;
      longest_gap = std::max(longest_gap, steps_since_trial);
      steps_since_trial = 0;
    }
    ++steps_since_trial;
    choice.record(choice.parallel() ? 1.0 : 2.0, 1);
  }
  EXPECT_EQ(longest_gap, ParallelLoopChoice::kLongestPeriods * 3);
  EXPECT_EQ(trials, 4 + (400 - 45 + 23) / 24);
  // Now one thread is faster: the next trials find it, and the period starts again at 3.
  while (choice.parallel()) choice.record(1.0, 1);
  choice.record(1.0, 1);  // one-thread trial
  choice.record(3.0, 1);  // all-thread trial, slower
  EXPECT_FALSE(choice.parallel());
  choice.record(1.0, 1);  // the last step of a period of 3
  EXPECT_FALSE(choice.parallel());  // the next one-thread trial...
  choice.record(1.0, 1);
  EXPECT_TRUE(choice.parallel());   // ...and its all-thread trial come 3 steps after the last ones
}

TEST(ParallelLoopChoice, AStepWithoutParticleStepsChangesNothing) {
  ParallelLoopChoice choice(3);
  EXPECT_FALSE(choice.parallel());
  choice.record(0.5, 0);
  EXPECT_FALSE(choice.parallel());  // still the one-thread trial
  choice.record(1.0, 10);
  EXPECT_TRUE(choice.parallel());
}

}  // namespace
}  // namespace talus
