// Tests of the expected end of a mud-flow run from its kinetic energy (run_end_estimate.hpp).
#include "talus/mudflow/run_end_estimate.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace talus {
namespace {

constexpr double kStep = 0.5;          // s: coarse step
constexpr double kStopFraction = 0.01;  // -
constexpr double kWallPerSecond = 0.1;  // s of wall time per simulated second

// A flow that accelerates for `rise` s to a peak of 1e9 J and then loses its kinetic energy
// exponentially with time constant `tau` (s): E = peak exp(-(t - rise) / tau).
double synthetic_energy(double t, double rise, double tau) {
  constexpr double peak = 1e9;
  return t <= rise ? peak * t / rise : peak * std::exp(-(t - rise) / tau);
}

TEST(RunEndEstimate, ExponentialDecayGivesTheTrueEnd) {
  const double rise = 30.0, tau = 25.0, duration = 600.0;
  const double true_end = rise + tau * std::log(1.0 / kStopFraction);  // 145.1 s
  RunEndEstimate estimate(duration, kStopFraction);
  for (double t = kStep; t < true_end; t += kStep) {
    estimate.record(t, synthetic_energy(t, rise, tau), kWallPerSecond * t);
    if (t <= rise) {
      EXPECT_EQ(estimate.expected_end(), duration) << "before the peak, t = " << t;
    } else if (t >= rise + 2.0) {  // a few steps of decay
      // 2% of the true end (measured: exact to rounding for an exact exponential).
      EXPECT_NEAR(estimate.expected_end(), true_end, 0.02 * true_end) << "t = " << t;
      EXPECT_NEAR(estimate.fraction_done(), t / true_end, 0.02) << "t = " << t;
      EXPECT_NEAR(estimate.wall_seconds_left(), kWallPerSecond * (true_end - t), 0.02 * kWallPerSecond * true_end);
    }
  }
}

TEST(RunEndEstimate, ShareDoneNeverDecreasesAndStaysBelowOneUntilTheEnd) {
  // A decay that slows down (the estimate moves later), a second surge (energy rising again: no
  // estimate, back to the duration), then a fast decay that passes its estimate.
  RunEndEstimate estimate(300.0, kStopFraction);
  for (int k = 1; k <= 400; ++k) {
    const double t = kStep * k;
    double energy = synthetic_energy(t, 20.0, 10.0 + 0.5 * t);
    if (t > 80.0 && t < 90.0) energy *= 1.0 + 0.2 * (t - 80.0);
    if (t >= 90.0) energy *= 3.0 * std::exp(-(t - 90.0));
    const double before = estimate.fraction_done();
    estimate.record(t, energy, kWallPerSecond * t);
    EXPECT_GE(estimate.fraction_done(), before) << "t = " << t;
    EXPECT_LT(estimate.fraction_done(), 1.0) << "t = " << t;
    EXPECT_GE(estimate.expected_end(), t) << "t = " << t;
    EXPECT_LE(estimate.expected_end(), 300.0) << "t = " << t;
  }
}

TEST(RunEndEstimate, NoDecayOrNoEnergyCriterionMeansTheDuration) {
  RunEndEstimate steady(200.0, kStopFraction);
  RunEndEstimate without_criterion(200.0, 0.0);
  for (double t = kStep; t <= 50.0; t += kStep) {
    steady.record(t, 1e6, t);
    without_criterion.record(t, synthetic_energy(t, 10.0, 5.0), t);
  }
  EXPECT_EQ(steady.expected_end(), 200.0);
  EXPECT_EQ(without_criterion.expected_end(), 200.0);
  EXPECT_DOUBLE_EQ(steady.fraction_done(), 50.0 / 200.0);
  // Everything at rest: the energy criterion ends the run now.
  steady.record(50.5, 0.0, 50.5);
  EXPECT_EQ(steady.expected_end(), 50.5);
  EXPECT_EQ(steady.wall_seconds_left(), 0.0);
}

}  // namespace
}  // namespace talus
