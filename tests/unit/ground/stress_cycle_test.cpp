// Tests of the stress cycle of paper 2.1, fig. 2 (ground/stress_cycle): the loop's area
// integrated along load-unload paths equals loop_energy, the footprint, reloading along the
// unloading line, the purely elastic limit, energy bookkeeping along a random path, and the
// degenerate inputs (k3 < k1, zero slopes, infinite yield pressure).
#include "talus/ground/stress_cycle.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace talus {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The built-in "talus, compact soil" class: k1 1e8 Pa/m, Y 8e5 Pa, k2 7e7 Pa/m, k3 1.9e8 Pa/m.
StressCycle talus_soil() {
  GroundMaterial material;
  material.elastic_slope = 1.0e8;
  material.yield_pressure = 8.0e5;
  material.plastic_slope = 7.0e7;
  material.unloading_slope = 1.9e8;
  return StressCycle::of(material);
}

// Work (J/m2) done on a piston along a path of pushes, by the trapezoid rule on the
// (compression, pressure) points the piston actually goes through.
class WorkMeter {
 public:
  explicit WorkMeter(const StressCycle& cycle) : cycle_(cycle) {}
  double push(double to) {
    const double before = state.compression;
    const double p = press(cycle_, state, to);
    work += 0.5 * (last_pressure_ + p) * (state.compression - before);
    last_pressure_ = p;
    return p;
  }
  // Pushes from the current compression to `to` in `steps` equal steps.
  void move_to(double to, int steps) {
    const double from = state.compression;
    for (int k = 1; k <= steps; ++k) push(from + (to - from) * k / steps);
  }

  PistonState state;
  double work = 0;

 private:
  const StressCycle& cycle_;
  double last_pressure_ = 0;
};

TEST(StressCycle, OfTakesTheMaterialsSlopes) {
  const StressCycle cycle = talus_soil();
  EXPECT_EQ(cycle.elastic_slope, 1.0e8);
  EXPECT_EQ(cycle.yield_pressure, 8.0e5);
  EXPECT_EQ(cycle.plastic_slope, 7.0e7);
  EXPECT_EQ(cycle.unloading_slope, 1.9e8);
}

TEST(StressCycle, LoadingCurveIsElasticThenPlastic) {
  const StressCycle cycle = talus_soil();
  const double yield_compression = 8.0e5 / 1.0e8;  // m
  // Closed forms of fig. 2; relative tolerance 1e-14 (a few roundings).
  EXPECT_NEAR(cycle.loading_pressure(0.5 * yield_compression), 4.0e5, 1e-14 * 4.0e5);
  EXPECT_NEAR(cycle.loading_pressure(0.02), 8.0e5 + 7.0e7 * (0.02 - yield_compression), 1e-14 * 2e6);
  EXPECT_NEAR(cycle.loading_work(0.5 * yield_compression), 0.5 * 1.0e8 * 0.004 * 0.004, 1e-14 * 800.0);
  const double work = 0.5 * 8.0e5 * yield_compression + 0.5 * (8.0e5 + cycle.loading_pressure(0.02)) * (0.02 - 0.008);
  EXPECT_NEAR(cycle.loading_work(0.02), work, 1e-14 * work);
  EXPECT_EQ(cycle.loading_pressure(-0.01), 0.0);
  EXPECT_EQ(cycle.loading_work(-0.01), 0.0);
}

// A full load (past yield) and unload path of 20 000 small steps: the trapezoid rule is exact on
// each straight piece and errs only in the step across the yield kink, by at most
// (k1 - k2) h^2 / 8 = 2e-5 J/m2 for h = 2.4e-6 m, against a loop of 1.5e4 J/m2 (1.4e-9
// relative). Tolerance 1e-6 relative.
TEST(StressCycle, LoopAreaOfAFullCycleEqualsLoopEnergy) {
  const StressCycle cycle = talus_soil();
  const double max_compression = 0.024;  // m, three times the yield compression
  WorkMeter meter(cycle);
  meter.move_to(max_compression, 10000);
  meter.move_to(0.0, 10000);
  const double loop = cycle.loop_energy(max_compression);
  EXPECT_GT(loop, 1.0e4);
  EXPECT_NEAR(meter.work, loop, 1e-6 * loop);
  EXPECT_EQ(pressure(cycle, meter.state), 0.0);
  EXPECT_EQ(stored_energy(cycle, meter.state), 0.0);
  EXPECT_NEAR(dissipated_energy(cycle, meter.state), loop, 1e-12 * loop);  // d_max within an ulp of 0.024
}

// The footprint after unloading is d_max - p_max / k3 computed by hand (relative 1e-14), and
// pushing the piston's top further out leaves it there, out of contact.
TEST(StressCycle, FootprintAfterUnloadingIsTheResidualCompression) {
  const StressCycle cycle = talus_soil();
  const double max_compression = 0.015;  // m
  const double max_pressure = 8.0e5 + 7.0e7 * (max_compression - 0.008);
  const double residual = max_compression - max_pressure / 1.9e8;
  PistonState state;
  EXPECT_NEAR(press(cycle, state, max_compression), max_pressure, 1e-14 * max_pressure);
  EXPECT_EQ(press(cycle, state, 0.0), 0.0);
  EXPECT_NEAR(state.compression, residual, 1e-14 * max_compression);
  EXPECT_NEAR(cycle.residual_compression(max_compression), residual, 1e-14 * max_compression);
  EXPECT_GT(residual, 0.0);
  EXPECT_EQ(press(cycle, state, -1.0), 0.0);
  EXPECT_EQ(state.compression, cycle.residual_compression(max_compression));
  EXPECT_EQ(press(cycle, state, std::numeric_limits<double>::quiet_NaN()), 0.0);
  EXPECT_EQ(state.compression, cycle.residual_compression(max_compression));
  EXPECT_EQ(state.max_compression, max_compression);
}

// After a cycle to d_max, reloading follows p_max - k3 (d_max - d) up to p_max, then the loading
// curve, and d_max, p_max move on. Pressures relative 1e-12 (a subtraction of nearby numbers).
TEST(StressCycle, ReloadingFollowsTheUnloadingLineThenTheLoadingCurve) {
  const StressCycle cycle = talus_soil();
  const double max_compression = 0.012;  // m
  PistonState state;
  const double max_pressure = press(cycle, state, max_compression);
  press(cycle, state, 0.0);
  const double residual = state.compression;
  for (int k = 1; k <= 10; ++k) {
    const double d = residual + (max_compression - residual) * k / 10.0;
    const double expected = max_pressure - 1.9e8 * (max_compression - d);
    EXPECT_NEAR(press(cycle, state, d), expected, 1e-12 * max_pressure) << "d = " << d;
    EXPECT_NEAR(pressure(cycle, state), expected, 1e-12 * max_pressure);
    EXPECT_LE(expected, cycle.loading_pressure(d) * (1.0 + 1e-12));
    EXPECT_EQ(state.max_compression, max_compression);
  }
  for (const double d : {0.013, 0.02, 0.03}) {
    EXPECT_NEAR(press(cycle, state, d), 8.0e5 + 7.0e7 * (d - 0.008), 1e-12 * max_pressure);
    EXPECT_EQ(state.max_compression, d);
    EXPECT_EQ(state.max_pressure, cycle.loading_pressure(d));
  }
}

// k3 = k1 and no yield: loading and unloading share one line, the piston springs back to 0, and
// all the work comes back (absolute 1e-9 of the peak work: rounding only, the path is straight).
TEST(StressCycle, PurelyElasticCycleDissipatesNothing) {
  StressCycle cycle;
  cycle.elastic_slope = 5.0e7;
  cycle.yield_pressure = kInfinity;
  cycle.plastic_slope = 1.0e6;
  cycle.unloading_slope = 5.0e7;
  const double max_compression = 0.5;  // m: far beyond any finite yield
  EXPECT_EQ(cycle.loading_pressure(max_compression), 5.0e7 * max_compression);
  EXPECT_DOUBLE_EQ(cycle.loading_work(max_compression), 0.5 * 5.0e7 * max_compression * max_compression);
  EXPECT_EQ(cycle.loop_energy(max_compression), 0.0);
  EXPECT_EQ(cycle.residual_compression(max_compression), 0.0);

  WorkMeter meter(cycle);
  meter.move_to(max_compression, 1000);
  const double peak_work = meter.work;
  EXPECT_NEAR(stored_energy(cycle, meter.state), peak_work, 1e-9 * peak_work);
  meter.move_to(-0.1, 1000);
  EXPECT_NEAR(meter.work, 0.0, 1e-9 * peak_work);
  EXPECT_EQ(meter.state.compression, 0.0);
  EXPECT_EQ(dissipated_energy(cycle, meter.state), 0.0);
}

// Along a random path of loads, partial unloads, reloads and releases out of contact, the work
// done always equals stored + dissipated energy. The trapezoid rule errs only in steps across a
// kink (yield, d_max): at most (k3 - k2) h^2 / 8 = 2.4e-5 J/m2 each for h <= 1.25e-6 m, at most
// two per segment, against work growing to about 2e5 J/m2 (measured gap 1e-9 relative).
// Tolerance 1e-6 relative to the largest work so far.
TEST(StressCycle, WorkDoneIsStoredPlusDissipatedAlongARandomPath) {
  const StressCycle cycle = talus_soil();
  std::mt19937_64 bits(20240611);
  const auto uniform = [&bits] { return static_cast<double>(bits() >> 11) * 0x1.0p-53; };
  WorkMeter meter(cycle);
  double pushed = 0.0;
  double largest_work = 0.0;
  double largest_gap = 0.0;
  int releases = 0;
  for (int segment = 0; segment < 120; ++segment) {
    // Targets from 2 mm above the footprint to 5 mm past the largest compression so far.
    const double low = cycle.residual_compression(meter.state.max_compression) - 0.002;
    const double target = low + (meter.state.max_compression + 0.005 - low) * uniform();
    const int steps = 1 + static_cast<int>(std::ceil(std::abs(target - pushed) / 1.25e-6));
    const double from = pushed;
    for (int k = 1; k <= steps; ++k) {
      pushed = from + (target - from) * k / steps;
      meter.push(pushed);
      const double balance = stored_energy(cycle, meter.state) + dissipated_energy(cycle, meter.state);
      largest_work = std::max(largest_work, meter.work);
      largest_gap = std::max(largest_gap, std::abs(meter.work - balance));
    }
    if (pressure(cycle, meter.state) == 0.0) ++releases;
  }
  EXPECT_GT(releases, 5);                                        // the path left contact
  EXPECT_GT(meter.state.max_compression, 0.008 * 3.0);           // and went well past yield
  EXPECT_LT(largest_gap, 1e-6 * largest_work);
}

// k3 < k1 is raised to k1: the footprint and loop area stay >= 0 and equal those of k3 = k1
// (exactly), for a cycle from a material and for one built by hand.
TEST(StressCycle, UnloadingSlopeBelowElasticSlopeIsRaised) {
  GroundMaterial material;
  material.elastic_slope = 1.0e8;
  material.yield_pressure = 8.0e5;
  material.plastic_slope = 7.0e7;
  material.unloading_slope = 2.0e7;
  EXPECT_EQ(StressCycle::of(material).unloading_slope, 1.0e8);

  StressCycle low{1.0e8, 8.0e5, 7.0e7, 2.0e7};
  StressCycle raised{1.0e8, 8.0e5, 7.0e7, 1.0e8};
  for (const double d : {0.004, 0.02}) {
    EXPECT_GE(low.residual_compression(d), 0.0);
    EXPECT_GE(low.loop_energy(d), 0.0);
    EXPECT_EQ(low.residual_compression(d), raised.residual_compression(d));
    EXPECT_EQ(low.loop_energy(d), raised.loop_energy(d));
  }
  PistonState state;
  press(low, state, 0.02);
  press(low, state, 0.015);
  EXPECT_EQ(stored_energy(low, state), stored_energy(raised, state));
}

// k1 = 0: no ground resistance at all, every quantity 0 and finite; the piston stays where it
// was pushed. k2 = 0: perfectly plastic at Y. Y = 0: plastic from the start.
TEST(StressCycle, ZeroSlopesAndZeroYield) {
  const StressCycle none{0.0, 8.0e5, 0.0, 0.0};
  PistonState state;
  EXPECT_EQ(press(none, state, 0.1), 0.0);
  EXPECT_EQ(press(none, state, 0.05), 0.0);
  EXPECT_EQ(state.compression, 0.1);
  EXPECT_EQ(stored_energy(none, state), 0.0);
  EXPECT_EQ(dissipated_energy(none, state), 0.0);
  EXPECT_EQ(none.residual_compression(0.1), 0.1);

  const StressCycle perfectly_plastic{1.0e8, 8.0e5, 0.0, 1.9e8};
  EXPECT_EQ(perfectly_plastic.loading_pressure(0.05), 8.0e5);
  // Triangle 0.5 Y d_y plus rectangle Y (d - d_y); relative 1e-14.
  EXPECT_NEAR(perfectly_plastic.loading_work(0.05), 0.5 * 8.0e5 * 0.008 + 8.0e5 * 0.042, 1e-14 * 4e4);

  const StressCycle no_yield{1.0e8, 0.0, 7.0e7, 1.9e8};
  EXPECT_EQ(no_yield.loading_pressure(0.01), 7.0e7 * 0.01);
  EXPECT_NEAR(no_yield.loading_work(0.01), 0.5 * 7.0e7 * 0.01 * 0.01, 1e-14 * 3.5e3);
}

}  // namespace
}  // namespace talus
