// Tests of the blow-up detection of the mud flow (docs/mudflow.md "Guard").
#include "talus/mudflow/flow_guard.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace talus {
namespace {

TEST(FlowGuard, EnergyOfTheColumns) {
  ParticleSet p;
  p.add(10.0, {0, 0, 105.0}, {3.0, 4.0, 0.0}, 1.0);
  p.add(20.0, {1, 0, 100.0}, {0, 0, 0}, 1.0);
  p.depth[0] = 2.0;
  p.depth[1] = 1.0;
  FootNormals normals;
  normals.resize(2);
  normals.z[0] = 0.5;
  const FlowEnergy e = flow_energy(p, normals, 10.0, 100.0);
  EXPECT_DOUBLE_EQ(e.kinetic, 0.5 * 10.0 * 25.0);
  EXPECT_DOUBLE_EQ(e.potential, 10.0 * 10.0 * 5.0);
  EXPECT_DOUBLE_EQ(e.internal, 0.5 * 10.0 * 10.0 * 0.5 * 2.0 + 0.5 * 20.0 * 10.0 * 1.0 * 1.0);
  EXPECT_DOUBLE_EQ(e.total(), e.kinetic + e.potential + e.internal);
}

TEST(FlowGuard, NotANumberAnywhereFails) {
  ParticleSet p;
  p.add(1.0, {0, 0, 0}, {0, 0, 0}, 1.0);
  EXPECT_TRUE(all_finite(p));
  p.density[0] = std::nan("");
  EXPECT_FALSE(all_finite(p));
  p.density[0] = 1.0;
  p.vy[0] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(all_finite(p));
}

TEST(FlowGuard, GrowthBeyondTheToleranceAndTheSourcesFails) {
  FlowEnergy before;
  before.kinetic = 600.0;
  before.internal = 400.0;
  before.potential = -5000.0;
  FlowEnergy after = before;
  EXPECT_FALSE(energy_blew_up(before, after, 0.0));
  after.kinetic += kEnergyGrowthTolerance * 1000.0 * 0.9;
  EXPECT_FALSE(energy_blew_up(before, after, 0.0));
  after.kinetic += kEnergyGrowthTolerance * 1000.0 * 0.2;
  EXPECT_TRUE(energy_blew_up(before, after, 0.0));
  EXPECT_FALSE(energy_blew_up(before, after, 50.0));  // entrained mass brought 50 J
  after.potential = std::nan("");
  EXPECT_TRUE(energy_blew_up(before, after, 0.0));
}

}  // namespace
}  // namespace talus
