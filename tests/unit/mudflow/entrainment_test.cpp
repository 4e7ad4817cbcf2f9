// Tests of Entrainment (paper 4.1; McDougall & Hungr 2005): the rate law E h |u| dt, the
// available depth, and conservation of momentum and of mud plus erodible material.
#include "talus/mudflow/entrainment.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../../validation/synthetic_ground.hpp"

namespace talus {
namespace {

using testing_ground::fast_material;
using testing_ground::local_spec;
using testing_ground::make_ground;

constexpr double kRho = 2000;  // kg/m3
constexpr double kRate = 0.01;  // E (1/m)

GroundModel slope_ground() {
  return make_ground(local_spec(20, 20, 2.0), [](double x, double y) { return 0.3 * x - 0.1 * y; },
                     fast_material(0.5, 0.8, 0.6));
}

// One flowing particle of mass m (kg), areal density sigma (kg/m2), depth h (m), velocity v.
ParticleSet one_particle(const GroundModel& ground, double x, double y, double mass, double sigma, double h,
                         const Eigen::Vector3d& v) {
  ParticleSet particles;
  particles.add(mass, {x, y, ground.elevation(x, y)}, v, 5.0);
  particles.density[0] = sigma;
  particles.depth[0] = h;
  return particles;
}

TEST(Entrainment, SmallStepFollowsTheRateLaw) {
  const GroundModel ground = slope_ground();
  const Grid<float> erodible(ground.spec(), 1.5f);
  Entrainment entrainment(ground, erodible, kRate, kRho);
  Grid<float> eroded(ground.spec(), 0.0f);
  const double mass = 1500, sigma = 1000, h = 0.8, dt = 1e-3;  // kg, kg/m2, m, s
  const Eigen::Vector3d v(3.0, -1.0, 0.5);                      // m/s
  ParticleSet particles = one_particle(ground, 13.1, -7.4, mass, sigma, h, v);
  const double volume = entrainment.erode(particles, {}, dt, eroded);
  // dz = E h |u| dt under the footprint m / sigma = 1.5 m2 (< 4 m2 cell), every cell under it
  // holding more than dz: exact to 1e-12.
  const double depth = kRate * h * v.norm() * dt;     // m
  const double expected = depth * (mass / sigma);     // m3
  EXPECT_NEAR(volume, expected, 1e-12 * expected);
  EXPECT_NEAR(particles.mass[0], mass + kRho * expected, 1e-12 * mass);
  // The footprint, a square of side sqrt(1.5) m centred on x 13.1 m, y -7.4 m, overlaps four
  // 2 m cells centred on multiples of 2 m; cell (7, 4) spans x 13..15 m, y -9..-7 m, so it
  // lost depth x its overlap / 4 m2. Float storage: 1e-6 relative.
  const double half = 0.5 * std::sqrt(1.5);
  const double overlap = (13.1 + half - 13.0) * (-7.0 - (-7.4 - half));  // m2
  EXPECT_NEAR(eroded.at(7, 4), depth * overlap / 4.0, 1e-6 * depth);
  double eroded_volume = 0;
  for (std::size_t cell = 0; cell < eroded.size(); ++cell) eroded_volume += 4.0 * eroded[cell];
  EXPECT_NEAR(eroded_volume, expected, 1e-6 * expected);
  EXPECT_NEAR(entrainment.remaining_volume(), 1.5 * 400 * 4.0 - expected, 1e-12 * 2400);
}

TEST(Entrainment, ACoarseParticleErodesEveryCellUnderIt) {
  // A particle of 36 m2 footprint (side 6 m: three 2 m cells when centred on a cell) erodes
  // depth E h |u| dt from all nine cells under it: 36 m2 x that depth, to 1e-12, with each
  // cell's eroded depth equal to it (float storage, 1e-6 relative), and nothing beyond them.
  const GroundModel ground = slope_ground();
  const Grid<float> erodible(ground.spec(), 2.0f);
  Entrainment entrainment(ground, erodible, kRate, kRho);
  Grid<float> eroded(ground.spec(), 0.0f);
  const double mass = 36000, sigma = 1000, h = 1.5, dt = 0.01;  // kg, kg/m2, m, s
  const Eigen::Vector3d v(4.0, 2.0, 0.0);                         // m/s
  ParticleSet particles = one_particle(ground, 20.0, -20.0, mass, sigma, h, v);
  const double depth = kRate * h * v.norm() * dt;  // m
  EXPECT_NEAR(entrainment.erode(particles, {}, dt, eroded), depth * 36.0, 1e-12 * depth * 36.0);
  int eroded_cells = 0;
  for (int row = 0; row < 20; ++row) {
    for (int col = 0; col < 20; ++col) {
      if (eroded.at(col, row) == 0.0f) continue;
      ++eroded_cells;
      EXPECT_NEAR(eroded.at(col, row), depth, 1e-6 * depth) << col << ", " << row;
      EXPECT_TRUE(col >= 9 && col <= 11 && row >= 9 && row <= 11) << col << ", " << row;
    }
  }
  EXPECT_EQ(eroded_cells, 9);
}

TEST(Entrainment, StopsAtTheAvailableDepth) {
  const GroundModel ground = slope_ground();
  Grid<float> erodible(ground.spec(), 0.0f);
  erodible.at(5, 5) = 0.1f;
  Entrainment entrainment(ground, erodible, kRate, kRho);
  Grid<float> eroded(ground.spec(), 0.0f);
  // sigma = 0: the footprint is one cell's area (4 m2), here exactly cell (5, 5) around its
  // centre (10 m, -10 m); a long step asks far more than 0.1 m.
  ParticleSet particles = one_particle(ground, 10.0, -10.0, 800, 0, 2.0, {10, 0, 3});
  const double available = static_cast<double>(0.1f) * 4.0;  // m3
  EXPECT_NEAR(entrainment.erode(particles, {}, 100.0, eroded), available, 1e-12 * available);
  EXPECT_EQ(entrainment.remaining_volume(), 0.0);
  EXPECT_NEAR(eroded.at(5, 5), 0.1f, 1e-7);  // float storage
  EXPECT_EQ(entrainment.erode(particles, {}, 100.0, eroded), 0.0);
  EXPECT_NEAR(particles.mass[0], 800 + kRho * available, 1e-12 * 800);
}

TEST(Entrainment, ConservesMomentumAndMudPlusBed) {
  const GroundModel ground = slope_ground();
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Grid<float> erodible(ground.spec(), 0.0f);
  for (std::size_t cell = 0; cell < erodible.size(); ++cell) erodible[cell] = static_cast<float>(0.3 * unit(random));
  Entrainment entrainment(ground, erodible, kRate, kRho);
  Grid<float> eroded(ground.spec(), 0.0f);
  ParticleSet particles;
  for (int k = 0; k < 300; ++k) {
    const double x = 38 * unit(random), y = -38 * unit(random);
    const std::size_t i = particles.add(200 + 800 * unit(random), {x, y, ground.elevation(x, y)},
                                        {4 * unit(random) - 2, 4 * unit(random) - 2, unit(random)}, 5.0);
    particles.density[i] = 2000 * unit(random);
    particles.depth[i] = 2 * unit(random);
  }
  const Eigen::Vector3d momentum = particles.total_momentum();
  const double total = particles.total_mass() / kRho + entrainment.remaining_volume();  // m3
  double entrained = 0;
  for (int step = 0; step < 50; ++step) entrained += entrainment.erode(particles, {}, 0.5, eroded);
  EXPECT_GT(entrained, 0.05 * entrainment.remaining_volume());  // the test erodes something
  // Momentum to 1e-12 relative; mud volume plus erodible volume to 1e-12 relative.
  EXPECT_LT((particles.total_momentum() - momentum).norm(), 1e-12 * momentum.norm());
  EXPECT_NEAR(particles.total_mass() / kRho + entrainment.remaining_volume(), total, 1e-12 * total);
}

TEST(Entrainment, OnlyActiveFlowingParticlesOnErodibleCellsErode) {
  const GroundModel ground = slope_ground();
  Grid<float> erodible(ground.spec(), 0.5f);
  erodible.at(2, 2) = -1.0f;
  erodible.at(3, 2) = std::numeric_limits<float>::quiet_NaN();
  erodible.at(4, 2) = static_cast<float>(erodible.spec().nodata);
  Entrainment entrainment(ground, erodible, kRate, kRho);
  EXPECT_NEAR(entrainment.remaining_volume(), 0.5 * 397 * 4.0, 1e-12 * 800);
  Grid<float> eroded(ground.spec(), 0.0f);
  ParticleSet particles;
  for (const double x : {4.0, 6.0, 8.0, 20.0, 22.0, 24.0}) particles.add(500, {x, -4.0, 0}, {2, 0, 0}, 5.0);
  for (std::size_t i = 0; i < particles.size(); ++i) particles.depth[i] = 1.0;
  particles.state[4] = ParticleState::deposited;
  const std::vector<char> active = {1, 1, 1, 1, 1, 0};
  // Cells (2..4, 2) hold nothing; particle 3 erodes; 4 is deposited, 5 inactive.
  EXPECT_GT(entrainment.erode(particles, active, 0.1, eroded), 0.0);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (i != 3) {
      EXPECT_EQ(particles.mass[i], 500.0) << "particle " << i;
    }
  }
  EXPECT_GT(particles.mass[3], 500.0);
}

}  // namespace
}  // namespace talus
