// Tests of the convergence measure of the Monte Carlo maps and the batch rule of --runs auto
// (envelope_convergence.hpp; docs/hazard-statistics.md, "Convergence"), on synthetic envelopes.
#include "talus/rockfall/envelope_convergence.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

// The envelope of `runs` synthetic runs: each crosses `length` consecutive cells of a 1000-cell
// strip, starting at a cell drawn from a binomial spread around 400, with an energy per passage
// drawn from an exponential of mean 5 kJ (the heavy-ish tail of real energies).
Envelope synthetic_envelope(std::uint64_t first_run, std::uint64_t runs) {
  std::vector<EnvelopeCell> cells;
  for (std::uint64_t run = first_run; run < first_run + runs; ++run) {
    std::mt19937_64 random(run);
    std::binomial_distribution<int> start(200, 0.5);
    std::exponential_distribution<double> energy(1.0 / 5000.0);
    const int first = 300 + start(random);
    for (int cell = first; cell < first + 40; ++cell) {
      cells.push_back({static_cast<std::uint32_t>(cell), 1, static_cast<std::uint64_t>(std::llround(energy(random)))});
    }
  }
  return envelope_of(cells);
}

TEST(EnvelopeConvergence, EnvelopeOfSortsAndAddsUpEqualCells) {
  const Envelope e = envelope_of({{7, 1, 100}, {2, 1, 5}, {7, 1, 40}, {2, 2, 1}});
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].cell, 2u);
  EXPECT_EQ(e[0].passages, 3u);
  EXPECT_EQ(e[0].energy, 6u);
  EXPECT_EQ(e[1].cell, 7u);
  EXPECT_EQ(e[1].passages, 2u);
  EXPECT_EQ(e[1].energy, 140u);
}

TEST(EnvelopeConvergence, SumsOfEnvelopesDoNotDependOnTheirOrder) {
  const Envelope a = synthetic_envelope(0, 7), b = synthetic_envelope(7, 5), c = synthetic_envelope(12, 9);
  const Envelope left = envelope_sum(envelope_sum(a, b), c);
  const Envelope right = envelope_sum(c, envelope_sum(b, a));
  ASSERT_EQ(left.size(), right.size());
  for (std::size_t i = 0; i < left.size(); ++i) {
    EXPECT_EQ(left[i].cell, right[i].cell);
    EXPECT_EQ(left[i].passages, right[i].passages);
    EXPECT_EQ(left[i].energy, right[i].energy);
  }
  const Envelope all = synthetic_envelope(0, 21);
  ASSERT_EQ(all.size(), left.size());
  for (std::size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i].passages, left[i].passages);
}

TEST(EnvelopeConvergence, PerRunMapsDivideByTheRuns) {
  const EnvelopeField f = per_run({{3, 5, 1000}}, 10);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].cell, 3u);
  EXPECT_DOUBLE_EQ(f[0].reach, 0.5);
  EXPECT_DOUBLE_EQ(f[0].energy, 100.0);
}

TEST(EnvelopeConvergence, ChangeIsTheRelativeL1DifferenceOfTheMaps) {
  // before (2 runs): cell 1 reached twice, 600 J; cell 2 once, 100 J.
  // after (4 runs): cell 1 three times, 800 J; cell 2 once, 100 J; cell 5 twice, 1100 J.
  const EnvelopeField before = per_run({{1, 2, 600}, {2, 1, 100}}, 2);
  const EnvelopeField after = per_run({{1, 3, 800}, {2, 1, 100}, {5, 2, 1100}}, 4);
  const EnvelopeChange change = envelope_change(before, after);
  EXPECT_EQ(change.reached_before, 2u);
  EXPECT_EQ(change.reached_after, 3u);
  // reach: |1 - 0.75| + |0.5 - 0.25| + |0 - 0.5| = 1.0 over 0.75 + 0.25 + 0.5 = 1.5
  EXPECT_DOUBLE_EQ(change.reach_change, 1.0 / 1.5);
  // energy: |300 - 200| + |50 - 25| + |0 - 275| = 400 over 200 + 25 + 275 = 500
  EXPECT_DOUBLE_EQ(change.energy_change, 400.0 / 500.0);
}

TEST(EnvelopeConvergence, SameMapsDoNotChangeAndDisjointHalvesChangeFully) {
  const Envelope half = synthetic_envelope(0, 10);
  EXPECT_EQ(envelope_change(per_run(half, 10), per_run(half, 10)).reach_change, 0.0);
  EXPECT_EQ(envelope_change(per_run(half, 10), per_run(envelope_sum(half, half), 20)).energy_change, 0.0);
  // The second half reaches only cells the first did not: f_n = f_n/2 / 2 + f_B / 2.
  Envelope shifted = half;
  for (EnvelopeCell& c : shifted) c.cell += 2000;
  const EnvelopeChange change = envelope_change(per_run(half, 10), per_run(envelope_sum(half, shifted), 20));
  EXPECT_NEAR(change.reach_change, 1.0, 1e-12);
  EXPECT_NEAR(change.energy_change, 1.0, 1e-12);
}

TEST(EnvelopeConvergence, NothingReachedIsNoChange) {
  const EnvelopeChange change = envelope_change({}, {});
  EXPECT_EQ(change.reach_change, 0.0);
  EXPECT_EQ(change.energy_change, 0.0);
  EXPECT_TRUE(envelope_converged(change, 0.05));
  const EnvelopeChange at_rest = envelope_change(per_run({{4, 1, 0}}, 1), per_run({{4, 2, 0}}, 2));
  EXPECT_EQ(at_rest.energy_change, 0.0);
}

// The measure's premise (and suggested_runs'): a Monte Carlo map's change over a doubling falls
// as 1 / sqrt(n); 16 times the runs, a quarter of the change.
TEST(EnvelopeConvergence, ChangeOfARandomMapFallsAsOneOverTheRootOfTheRuns) {
  const auto doubling_change = [](std::uint64_t n) {
    return envelope_change(per_run(synthetic_envelope(0, n / 2), n / 2), per_run(synthetic_envelope(0, n), n));
  };
  const EnvelopeChange at_100 = doubling_change(100), at_1600 = doubling_change(1600);
  EXPECT_GT(at_100.reach_change, 0.01);
  EXPECT_NEAR(at_100.reach_change / at_1600.reach_change, 4.0, 1.2);
  EXPECT_NEAR(at_100.energy_change / at_1600.energy_change, 4.0, 1.2);
}

TEST(EnvelopeConvergence, ConvergedMeansBothChangesBelowTheTolerance) {
  EXPECT_TRUE(envelope_converged({10, 10, 0.049, 0.01}, 0.05));
  EXPECT_FALSE(envelope_converged({10, 10, 0.05, 0.01}, 0.05));
  EXPECT_FALSE(envelope_converged({10, 10, 0.01, 0.2}, 0.05));
}

TEST(EnvelopeConvergence, TheRunLimitIsTheLastDoublingOfTheMinimumNotAboveTheMaximum) {
  EXPECT_EQ(auto_run_limit({0.05, 20, 1280}), 1280u);
  EXPECT_EQ(auto_run_limit({0.05, 20, 1279}), 640u);
  EXPECT_EQ(auto_run_limit({0.05, 20, 1000}), 640u);
  EXPECT_EQ(auto_run_limit({0.05, 20, 20}), 20u);
  EXPECT_EQ(auto_run_limit({0.05, 10, 39}), 20u);
}

TEST(EnvelopeConvergence, SuggestedRunsExtrapolateAsOneOverTheRootOfTheRuns) {
  // Twice the tolerance: four times the runs.
  EXPECT_EQ(suggested_runs(10, {10, 10, 0.10, 0.02}, 0.05), 40u);
  // The larger change decides; rounded up to tens: 10 x (0.21 / 0.05)^2 = 176.4.
  EXPECT_EQ(suggested_runs(10, {10, 10, 0.07, 0.21}, 0.05), 180u);
  // Converged: as many as were run.
  EXPECT_EQ(suggested_runs(640, {10, 10, 0.01, 0.02}, 0.05), 640u);
  // Just over the tolerance: still more than were run.
  EXPECT_GT(suggested_runs(100, {10, 10, 0.0500001, 0.0}, 0.05), 100u);
}

TEST(EnvelopeConvergence, TheGridAddsMapsInAnyOrder) {
  const EnvelopeField a = per_run(synthetic_envelope(0, 3), 3), b = per_run(synthetic_envelope(3, 7), 7);
  EnvelopeGrid forward(1000), backward(1000);
  forward.add(a);
  forward.add(b);
  backward.add(b);
  backward.add(a);
  const EnvelopeField f = forward.field(), g = backward.field();
  ASSERT_EQ(f.size(), g.size());
  for (std::size_t i = 0; i < f.size(); ++i) {
    EXPECT_EQ(f[i].cell, g[i].cell);
    EXPECT_EQ(f[i].reach, g[i].reach);
    EXPECT_EQ(f[i].energy, g[i].energy);
  }
  // Cell 400 is on most paths: its reach is the sum of both sources' reach.
  double expected = 0;
  for (const EnvelopeField* field : {&a, &b}) {
    for (const FieldCell& c : *field) expected += c.cell == 400 ? c.reach : 0.0;
  }
  bool found = false;
  for (const FieldCell& c : f) {
    if (c.cell != 400) continue;
    found = true;
    EXPECT_NEAR(c.reach, expected, 1e-9);
  }
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace talus
