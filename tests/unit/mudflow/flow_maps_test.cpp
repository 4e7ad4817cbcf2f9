// Tests of FlowMaps (docs/architecture.md section 3, mud-flow layers): volume-conserving spreading of the
// particles onto the DEM cells, depth normal to the ground, maxima, arrival time, nodata.
#include "talus/mudflow/flow_maps.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../../validation/synthetic_ground.hpp"
#include "talus/mudflow/flow_density.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus {
namespace {

using testing_ground::fast_material;
using testing_ground::local_spec;
using testing_ground::make_ground;

constexpr double kRho = 2000;  // kg/m3

// A square sheet of particles of vertical column depth `column` (m) over [x0, x1] x [y0, y1]
// (m), lattice step s (m), all with velocity (u, 0, 0) (m/s).
ParticleSet sheet(const GroundModel& ground, double x0, double x1, double y0, double y1, double s, double column,
                  double u) {
  ParticleSet particles;
  for (double y = y0 + 0.5 * s; y < y1; y += s) {
    for (double x = x0 + 0.5 * s; x < x1; x += s) {
      particles.add(kRho * column * s * s, {x, y, ground.elevation(x, y)}, {u, 0, 0}, kSupportPerSpacing * s);
    }
  }
  return particles;
}

// A curved ground (cos(theta) differs from cell to cell), 1 m cells.
GroundModel curved_ground() {
  return make_ground(local_spec(30, 30, 1.0),
                     [](double x, double y) { return 0.02 * x * x - 0.3 * y + 0.5 * std::sin(0.2 * x * y); },
                     fast_material(0.5, 0.8, 0.6));
}

TEST(FlowMaps, DepositHoldsTheVolumeOfOneParticleAnywhere) {
  const GroundModel ground = curved_ground();
  // Interior, near the edge (footprint cut by the DEM), and a small radius between four cell
  // centres (spread over 1.5 cells instead). Tolerance 1e-12 relative.
  const std::vector<std::array<double, 3>> cases = {
      {12.3, -14.7, 2.4}, {0.2, -0.1, 3.0}, {28.9, -28.6, 6.0}, {10.5, -10.5, 0.3}, {5.02, -17.9, 1.1}};
  for (const auto& [x, y, radius] : cases) {
    ParticleSet particles;
    particles.add(1234.5, {x, y, ground.elevation(x, y)}, {0, 0, 0}, radius);
    FlowMaps maps(ground, kRho, 0.05, false);
    const double volume = maps.deposit(particles);
    EXPECT_NEAR(volume, 1234.5 / kRho, 1e-12 * 1234.5 / kRho) << "particle at " << x << ", " << y;
  }
}

// Interior cells of a uniform sheet of lattice step s (m): depth = column x cos(theta), within
// 2%. With s = 0.5 m the lattice repeats every cell (measured error 1e-8, float storage); with
// s = 0.7 m it does not and the kernel's sampling by the cell centres shows (measured 1.5%).
void expect_sheet_depth(double slope, double s) {
  const GroundModel ground =
      make_ground(local_spec(40, 40, 1.0), [&](double x, double) { return slope * x; }, fast_material(0.5, 0.8, 0.6));
  const double column = 2.0;  // m, vertical
  const ParticleSet particles = sheet(ground, 5, 35, -35, -5, s, column, 1.0);
  FlowMaps maps(ground, kRho, 0.05, false);
  maps.sample(particles, 0.0);
  maps.deposit(particles);
  const double expected = column / std::sqrt(1 + slope * slope);
  double worst = 0;
  for (int row = 10; row <= 29; ++row) {  // cells at least 4 m (> R = 2.4 s) inside the sheet
    for (int col = 10; col <= 29; ++col) {
      const double flow = maps.layers().flow_depth_max.at(col, row);
      const double left = maps.layers().deposit_depth.at(col, row);
      worst = std::max({worst, std::abs(flow / expected - 1), std::abs(left / expected - 1)});
    }
  }
  EXPECT_LT(worst, 0.02) << "slope " << slope << ", spacing " << s;
}

TEST(FlowMaps, UniformSheetGivesItsDepthNormalToTheGround) {
  for (const double s : {0.5, 0.7}) {
    expect_sheet_depth(0.0, s);
    expect_sheet_depth(0.7, s);
  }
}

// A sheet of particles of spacing s (m) on a square lattice turned by `angle` (rad) about
// (x0, y0), clipped to [x0 - half, x0 + half] x [y0 - half, y0 + half] (m); vertical column
// depth `column` (m), at rest.
ParticleSet turned_sheet(const GroundModel& ground, double x0, double y0, double half, double s, double angle,
                         double column) {
  ParticleSet particles;
  const double c = std::cos(angle), n = std::sin(angle);
  const int steps = static_cast<int>(std::ceil(1.5 * half / s));
  for (int j = -steps; j <= steps; ++j) {
    for (int i = -steps; i <= steps; ++i) {
      const double a = (i + 0.5) * s, b = (j + 0.5) * s;
      const double x = x0 + c * a - n * b, y = y0 + n * a + c * b;
      if (std::abs(x - x0) > half || std::abs(y - y0) > half) continue;
      particles.add(kRho * column * s * s, {x, y, ground.elevation(x, y)}, {0, 0, 0}, kSupportPerSpacing * s);
    }
  }
  return particles;
}

// Particles much smaller than the cells (2.5 m spacing, R = 6 m, on 10 m cells), on lattices
// turned against the grid so that no two cells see the same pattern: every interior cell's depth
// is the column x cos(theta) within 2% (measured worst: 0.0012% with the spreading radius of
// 15 m; 23% when spreading only within R). The lattice along the grid repeats every cell and is
// exact either way.
TEST(FlowMaps, ParticlesSmallerThanTheCellsGiveSmoothDepths) {
  const double cell = 10.0, s = 2.5, column = 2.0;  // m
  for (const double slope : {0.0, 0.7}) {
    const GroundModel ground = make_ground(local_spec(40, 40, cell), [&](double x, double) { return slope * x; },
                                           fast_material(0.5, 0.8, 0.6));
    const double expected = column / std::sqrt(1 + slope * slope);
    for (const double angle : {0.0, 0.3, 0.5236, 0.7854}) {
      const ParticleSet particles = turned_sheet(ground, 196.3, -197.1, 150.0, s, angle, column);
      FlowMaps maps(ground, kRho, 0.05, false);
      maps.sample(particles, 0.0);
      maps.deposit(particles);
      double worst = 0;
      for (int row = 8; row <= 31; ++row) {  // cell centres at least 25 m (> 15 m) inside the sheet
        for (int col = 8; col <= 31; ++col) {
          const double flow = maps.layers().flow_depth_max.at(col, row);
          const double left = maps.layers().deposit_depth.at(col, row);
          worst = std::max({worst, std::abs(flow / expected - 1), std::abs(left / expected - 1)});
        }
      }
      RecordProperty("worst_slope" + std::to_string(slope) + "_angle" + std::to_string(angle), std::to_string(worst));
      EXPECT_LT(worst, 0.02) << "slope " << slope << ", lattice turned by " << angle << " rad";
    }
  }
}

// A lone particle on flat ground whose density sum has thinned it to its widest smoothing
// radius, 4 R (flow_density.hpp): the map draws it as deep as the dynamics see it,
// sigma / rho0 = m W(0, 4 R) / rho0, within 2% on 1 m cells (1 / 16 of what its support radius
// R alone would draw), and spreads it over the cells within 4 R, no farther (nodes on whole
// metres, the particle on one).
TEST(FlowMaps, ALoneThinnedParticleIsDrawnAsDeepAsItsDensity) {
  const GroundModel ground = make_ground(local_spec(120, 120, 1.0), [](double, double) { return 0.0; },
                                         fast_material(0.5, 0.8, 0.6));
  const double mass = 5e4, support = 6.0, widest = kLargestSmoothingGrowth * support;  // kg, m, m
  ParticleSet particles;
  particles.add(mass, {60.0, -60.0, 0.0}, {1, 0, 0}, support);
  particles.density[0] = mass * kernel_value(0.0, widest);  // kg/m2
  FlowMaps maps(ground, kRho, 0.0, false);
  maps.sample(particles, 0.0);
  const Grid<float>& depth = maps.layers().flow_depth_max;
  const double expected = particles.density[0] / kRho;  // m
  EXPECT_NEAR(depth.at(60, 60), expected, 0.02 * expected);
  double reach = 0;  // m: the farthest reached cell centre from the particle
  for (int row = 0; row < 120; ++row) {
    for (int col = 0; col < 120; ++col) {
      if (depth.at(col, row) > 0.0f) reach = std::max(reach, std::hypot(col - 60.0, row - 60.0));
    }
  }
  EXPECT_GT(reach, widest - 1.0);
  EXPECT_LT(reach, widest);
}

TEST(FlowMaps, MaximaKeepTheLargestSampleAndPressureIsRhoUSquared) {
  const GroundModel ground =
      make_ground(local_spec(20, 20, 1.0), [](double, double) { return 0.0; }, fast_material(0.5, 0.8, 0.6));
  FlowMaps maps(ground, kRho, 0.05, false);
  // (column depth m, speed m/s) at three sample times: the depth and speed maxima come from
  // different samples.
  maps.sample(sheet(ground, 2, 18, -18, -2, 0.5, 1.0, 3.0), 1.0);
  maps.sample(sheet(ground, 2, 18, -18, -2, 0.5, 2.0, 1.0), 2.0);
  maps.sample(sheet(ground, 2, 18, -18, -2, 0.5, 0.5, 2.0), 3.0);
  const FlowLayers& layers = maps.layers();
  // Interior cell: depth 2 m within 2%, speed 3 m/s and pressure 2000 x 9 / 1000 = 18 kPa to
  // float rounding (1e-6 relative).
  EXPECT_NEAR(layers.flow_depth_max.at(10, 10), 2.0, 0.04);
  EXPECT_NEAR(layers.velocity_max.at(10, 10), 3.0, 3e-6);
  EXPECT_NEAR(layers.pressure_max.at(10, 10), 18.0, 18e-6);
}

TEST(FlowMaps, PressureIsRhoTimesTheCellSpeedSquared) {
  const GroundModel ground =
      make_ground(local_spec(20, 20, 1.0), [](double, double) { return 0.0; }, fast_material(0.5, 0.8, 0.6));
  ParticleSet particles;
  particles.add(3000, {8.2, -9.1, 0}, {2.0, 1.0, 0}, 2.5);
  particles.add(1000, {9.7, -9.6, 0}, {-4.0, 0.5, 0}, 2.0);
  FlowMaps maps(ground, kRho, 0.05, false);
  maps.sample(particles, 0.0);
  const FlowLayers& layers = maps.layers();
  int checked = 0;
  bool mixed = false;  // some cell's speed lies strictly between the two particles' speeds
  for (std::size_t cell = 0; cell < layers.velocity_max.size(); ++cell) {
    const double u = layers.velocity_max[cell];
    if (u == 0.0f) continue;
    ++checked;
    mixed = mixed || (u > std::sqrt(5.0) + 1e-3 && u < std::sqrt(16.25) - 1e-3);
    // Float rounding of the stored speed and pressure: 1e-6 relative.
    EXPECT_NEAR(layers.pressure_max[cell], kRho * u * u / 1000, 1e-6 * kRho * u * u / 1000);
  }
  EXPECT_GT(checked, 10);
  EXPECT_TRUE(mixed);
}

TEST(FlowMaps, ArrivalIsTheFirstSampleAboveTheThresholdAndDepositedParticlesDoNotFlow) {
  const GroundModel ground =
      make_ground(local_spec(20, 20, 1.0), [](double, double) { return 0.0; }, fast_material(0.5, 0.8, 0.6));
  const double threshold = 0.1;  // m
  FlowMaps maps(ground, kRho, threshold, false);
  // One particle at a cell centre; its depth there is m / rho0 x w_c, w_c its normalised weight.
  auto particle_of_mass = [&](double mass) {
    ParticleSet particles;
    particles.add(mass, {10, -10, 0}, {1, 0, 0}, 3.0);
    return particles;
  };
  FlowMaps probe(ground, kRho, threshold, false);
  probe.sample(particle_of_mass(kRho), 0.0);
  const double depth_per_cubic_metre = probe.layers().flow_depth_max.at(10, 10);  // m per m3
  const double below = 0.8 * threshold / depth_per_cubic_metre * kRho;               // kg
  const double above = 1.25 * threshold / depth_per_cubic_metre * kRho;              // kg
  ParticleSet stopped = particle_of_mass(10 * above);
  stopped.state[0] = ParticleState::deposited;
  maps.sample(stopped, 0.5);
  maps.sample(particle_of_mass(below), 1.0);
  maps.sample(particle_of_mass(above), 1.5);
  maps.sample(particle_of_mass(2 * above), 2.0);
  const FlowLayers& layers = maps.layers();
  EXPECT_EQ(layers.arrival_time.at(10, 10), 1.5f);
  EXPECT_EQ(layers.arrival_time.at(2, 2), 0.0f);  // never reached
  // The deposited particle was not sampled: the maximum is that of 2 x above, within float
  // rounding (1e-6 relative).
  EXPECT_NEAR(layers.flow_depth_max.at(10, 10), 2.5 * threshold, 2.5e-6 * threshold);
}

// Issue 17: 0 means "never reached", so the release area (reached at t = 0) must hold a time
// above 0, or its legend and overviews would show it as never reached.
TEST(FlowMaps, CellsCoveredAtReleaseHoldAnArrivalTimeAboveZero) {
  const GroundModel ground =
      make_ground(local_spec(20, 20, 1.0), [](double, double) { return 0.0; }, fast_material(0.5, 0.8, 0.6));
  FlowMaps maps(ground, kRho, 0.05, false);
  ParticleSet particles;
  particles.add(5000, {10, -10, 0}, {0, 0, 0}, 3.0);
  maps.sample(particles, 0.0);
  EXPECT_FLOAT_EQ(maps.layers().arrival_time.at(10, 10), 0.001f);
  EXPECT_EQ(maps.layers().arrival_time.at(2, 2), 0.0f);  // never reached
}

TEST(FlowMaps, NodataOutsideTheValidAreaAndZeroInUnreachedCells) {
  GridSpec spec = local_spec(20, 20, 1.0);
  Grid<double> z(spec, 5.0);
  for (int row = 0; row < 20; ++row) {
    for (int col = 12; col < 20; ++col) z.at(col, row) = spec.nodata;
  }
  const GroundModel ground(std::move(z), Grid<GroundMaterial>(spec, fast_material(0.5, 0.8, 0.6)));
  FlowMaps maps(ground, kRho, 0.05, true);
  ParticleSet particles;
  particles.add(5000, {10.8, -7.0, 5.0}, {2, 0, 0}, 4.0);  // its support reaches the invalid cells
  maps.sample(particles, 1.0);
  maps.add_erosion(ground.elevation_grid().index(3, 3), 0.25);
  const double volume = maps.deposit(particles);
  EXPECT_NEAR(volume, 5000 / kRho, 1e-12 * 5000 / kRho);  // all of it in valid cells
  const FlowLayers& layers = maps.layers();
  const std::vector<const Grid<float>*> grids = {&layers.flow_depth_max, &layers.velocity_max, &layers.pressure_max,
                                                 &layers.deposit_depth,  &layers.arrival_time,  &*layers.erosion_depth};
  for (const Grid<float>* grid : grids) {
    for (int row = 0; row < 20; ++row) {
      for (int col = 12; col < 20; ++col) EXPECT_EQ(grid->at(col, row), static_cast<float>(spec.nodata));
      EXPECT_EQ(grid->at(0, row), 0.0f);  // valid, unreached
    }
  }
  // Reached, next to the invalid area (every layer but erosion).
  for (std::size_t k = 0; k + 1 < grids.size(); ++k) EXPECT_GT(grids[k]->at(11, 7), 0.0f);
  EXPECT_EQ(layers.erosion_depth->at(3, 3), 0.25f);
}

}  // namespace
}  // namespace talus
