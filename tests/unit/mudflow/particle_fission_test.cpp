// Tests of the pressure-contrast criterion and the 1 -> 4 split (paper 4.2, fig. 8a).
#include "talus/mudflow/particle_fission.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "adaptivity_fixtures.hpp"
#include "talus/mudflow/flow_density.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus {
namespace {

using adaptivity_fixtures::binned;
using adaptivity_fixtures::plane_ground;
using adaptivity_fixtures::radius_of_spacing;
using adaptivity_fixtures::set_sph_density;

// A square lattice of columns x columns particles of `spacing` (m) centred on (cx, cy), each of
// the mass of a 1 m deep column of mud (kg).
ParticleSet lattice(const GroundModel& ground, int columns, double spacing, double cx, double cy) {
  ParticleSet particles;
  const double mass = 1800.0 * spacing * spacing;
  for (int row = 0; row < columns; ++row) {
    for (int col = 0; col < columns; ++col) {
      const double x = cx + (col - 0.5 * (columns - 1)) * spacing, y = cy + (row - 0.5 * (columns - 1)) * spacing;
      particles.add(mass, {x, y, ground.elevation(x, y)}, Eigen::Vector3d::Zero(), radius_of_spacing(spacing));
    }
  }
  set_sph_density(particles);
  return particles;
}

// Sum of |m v| (kg m/s): the scale of momentum errors.
double momentum_scale(const ParticleSet& particles) {
  double sum = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) sum += particles.mass[i] * particles.velocity(i).norm();
  return sum;
}

// One flowing particle of spacing 8 m at low pressure next to a deposited one of high pressure:
// only the flowing one can split, and its contrast is far above 0.5.
ParticleSet pressure_step_pair(const GroundModel& ground, double spacing) {
  ParticleSet particles;
  const double x = 100.3, y = -87.7;
  const std::size_t parent = particles.add(5000.0, {x, y, ground.elevation(x, y)}, {1.5, -0.7, 0.2},
                                           radius_of_spacing(spacing));
  const std::size_t other = particles.add(5000.0, {x + spacing, y, ground.elevation(x + spacing, y)},
                                          Eigen::Vector3d::Zero(), radius_of_spacing(spacing));
  particles.state[other] = ParticleState::deposited;
  set_sph_density(particles);
  particles.pressure[parent] = 1000.0;
  particles.pressure[other] = 50000.0;
  particles.level[parent] = 3;
  particles.still_time[parent] = 0.25;
  return particles;
}

TEST(ParticleFission, PressureContrastIsZeroInAUniformField) {
  const GroundModel ground = plane_ground();
  ParticleSet particles = lattice(ground, 11, 5.0, 100.0, -100.0);
  std::fill(particles.pressure.begin(), particles.pressure.end(), 20000.0);
  const PairSearch search = binned(particles);
  // Interior particle (the centre, index 60): equal pressures give no gradient; tolerance 1e-12.
  EXPECT_NEAR(pressure_contrast(particles, search, 60), 0.0, 1e-12);
}

TEST(ParticleFission, PressureContrastMatchesALinearPressureGradient) {
  const GroundModel ground = plane_ground();
  const double spacing = 5.0, base = 20000.0, gx = 300.0, gy = -200.0;  // m, Pa, Pa/m, Pa/m
  ParticleSet particles = lattice(ground, 15, spacing, 100.0, -100.0);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    particles.pressure[i] = base + gx * (particles.x[i] - 100.0) + gy * (particles.y[i] + 100.0);
  }
  const PairSearch search = binned(particles);
  const std::size_t centre = 7 * 15 + 7;
  const double expected = spacing * std::hypot(gx, gy) / base;  // about 0.09
  // SPH gradient of a linear field on a lattice, with SPH densities (the plain sum is 5.3% low
  // here): within 5%.
  EXPECT_NEAR(pressure_contrast(particles, search, centre), expected, 0.05 * expected);
}

TEST(ParticleFission, PressureContrastMatchesALinearPressureGradientAtTheFlowEdge) {
  const GroundModel ground = plane_ground();
  const double spacing = 5.0, base = 20000.0, gx = 300.0, gy = -200.0;  // m, Pa, Pa/m, Pa/m
  ParticleSet particles = lattice(ground, 15, spacing, 100.0, -100.0);
  const std::size_t edge = 7;  // middle of the first row: neighbours on one side only
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double dx = particles.x[i] - particles.x[edge], dy = particles.y[i] - particles.y[edge];  // m
    particles.pressure[i] = base + gx * dx + gy * dy;
  }
  const PairSearch search = binned(particles);
  const double expected = spacing * std::hypot(gx, gy) / base;
  // One-sided neighbours (the plain SPH sum is 21% low here): within 5%.
  EXPECT_NEAR(pressure_contrast(particles, search, edge), expected, 0.05 * expected);
}

TEST(ParticleFission, PressureContrastsAreZeroForDepositedParticles) {
  const GroundModel ground = plane_ground();
  ParticleSet particles = pressure_step_pair(ground, 8.0);
  const PairSearch search = binned(particles);
  const std::vector<double> contrast = pressure_contrasts(particles, search);
  // The flowing particle gets its contrast (exactly the single-particle value), the deposited one 0.
  EXPECT_EQ(contrast[0], pressure_contrast(particles, search, 0));
  EXPECT_GT(contrast[0], 0.5);
  EXPECT_EQ(contrast[1], 0.0);
}

TEST(ParticleFission, ChildrenStandOnTheQuartersOfTheParentFootprint) {
  const GroundModel ground = plane_ground();
  const double spacing = 8.0;  // m
  ParticleSet particles = pressure_step_pair(ground, spacing);
  const ParticleSet before = particles;
  const PairSearch search = binned(particles);
  ASSERT_EQ(split_particles(particles, search, ground, FissionRule{}), 1u);
  ASSERT_EQ(particles.size(), 5u);
  // The parent's slot holds the first child, children 2-4 are appended after the other particle.
  const std::vector<std::size_t> children{0, 2, 3, 4};
  const double offsets[4][2] = {{-2.0, -2.0}, {2.0, -2.0}, {-2.0, 2.0}, {2.0, 2.0}};  // m: s / 4
  for (std::size_t c = 0; c < 4; ++c) {
    const std::size_t k = children[c];
    // Positions to 1e-12 m; z on the ground to 1e-12 m; mass, radius, velocity, level, still
    // time exactly.
    EXPECT_NEAR(particles.x[k], before.x[0] + offsets[c][0], 1e-12);
    EXPECT_NEAR(particles.y[k], before.y[0] + offsets[c][1], 1e-12);
    EXPECT_NEAR(particles.z[k], ground.elevation(particles.x[k], particles.y[k]), 1e-12);
    EXPECT_EQ(particles.mass[k], 0.25 * before.mass[0]);
    EXPECT_EQ(particles.radius[k], 0.5 * before.radius[0]);
    EXPECT_EQ(particles.velocity(k), before.velocity(0));
    EXPECT_EQ(particles.level[k], 3);
    EXPECT_EQ(particles.still_time[k], 0.25);
    EXPECT_EQ(particles.state[k], ParticleState::flowing);
  }
  // The deposited particle is untouched.
  EXPECT_EQ(particles.x[1], before.x[1]);
  EXPECT_EQ(particles.mass[1], before.mass[1]);
  EXPECT_EQ(particles.state[1], ParticleState::deposited);
}

TEST(ParticleFission, NoSplitBelowTheSmallestSpacing) {
  const GroundModel ground = plane_ground();
  const FissionRule rule{0.5, 4.0};
  {
    // Spacing 4 m = smallest: never splits although its contrast is far above the threshold.
    ParticleSet particles = pressure_step_pair(ground, 4.0);
    const PairSearch search = binned(particles);
    ASSERT_GT(pressure_contrast(particles, search, 0), rule.threshold);
    EXPECT_EQ(split_particles(particles, search, ground, rule), 0u);
    EXPECT_EQ(particles.size(), 2u);
    EXPECT_EQ(particles.radius[0], radius_of_spacing(4.0));
  }
  {
    // Spacing 8 m: splits into children of exactly the smallest spacing.
    ParticleSet particles = pressure_step_pair(ground, 8.0);
    const PairSearch search = binned(particles);
    EXPECT_EQ(split_particles(particles, search, ground, rule), 1u);
    EXPECT_NEAR(particles.radius[0] / kSupportPerSpacing, 4.0, 1e-12);
  }
}

// Crowded fusion's floor (docs/mudflow.md section 8): a particle whose natural smoothing radius is
// at most the floor would give four children all summed over the floor: it does not split.
TEST(ParticleFission, NoSplitOfAParticleHeldAtTheSmoothingFloor) {
  const GroundModel ground = plane_ground();
  ParticleSet particles = pressure_step_pair(ground, 8.0);
  const double natural = natural_smoothing_radius(particles, 0);  // m
  const PairSearch search = binned(particles);
  ASSERT_GT(pressure_contrast(particles, search, 0), 0.5);
  EXPECT_EQ(split_particles(particles, search, ground, FissionRule{0.5, 4.0, natural}), 0u);
  EXPECT_EQ(particles.size(), 2u);
  // A floor just below its natural radius: it splits.
  EXPECT_EQ(split_particles(particles, search, ground, FissionRule{0.5, 4.0, 0.999 * natural}), 1u);
}

TEST(ParticleFission, NoSplitWhenAChildWouldLeaveTheGround) {
  const GroundModel ground = plane_ground();
  ParticleSet particles;
  // 1 m inside the east edge (x = 200 m): the eastern children (x + 2 m) would be off the ground.
  const double spacing = 8.0, x = 199.0, y = -100.0;
  particles.add(5000.0, {x, y, ground.elevation(x, y)}, Eigen::Vector3d::Zero(), radius_of_spacing(spacing));
  particles.add(5000.0, {x - spacing, y, ground.elevation(x - spacing, y)}, Eigen::Vector3d::Zero(),
                radius_of_spacing(spacing));
  particles.state[1] = ParticleState::deposited;
  set_sph_density(particles);
  particles.pressure = {1000.0, 50000.0};
  const PairSearch search = binned(particles);
  ASSERT_GT(pressure_contrast(particles, search, 0), 0.5);
  EXPECT_EQ(split_particles(particles, search, ground, FissionRule{}), 0u);
  EXPECT_EQ(particles.size(), 2u);
}

TEST(ParticleFission, SplitConservesMassAndMomentumOnARandomCloud) {
  const GroundModel ground = plane_ground();
  std::mt19937_64 random(20240905);
  std::uniform_real_distribution<double> coordinate(20.0, 180.0), unit(0.0, 1.0), speed(-5.0, 5.0);
  ParticleSet particles;
  for (int k = 0; k < 500; ++k) {
    const double x = coordinate(random), y = -coordinate(random);
    const double spacing = unit(random) < 0.5 ? 4.0 : 8.0;                      // m
    const double mass = 1000.0 * spacing * spacing * (0.5 + unit(random));      // kg
    particles.add(mass, {x, y, ground.elevation(x, y)}, {speed(random), speed(random), speed(random)},
                  radius_of_spacing(spacing));
  }
  set_sph_density(particles);
  for (double& p : particles.pressure) p = 1000.0 + 50000.0 * unit(random);  // Pa
  const double mass_before = particles.total_mass();
  const Eigen::Vector3d momentum_before = particles.total_momentum();
  const double scale = momentum_scale(particles);
  const PairSearch search = binned(particles);

  const std::size_t splits = split_particles(particles, search, ground, FissionRule{0.5, 2.0});
  // The random pressures make many particles split.
  EXPECT_GT(splits, 100u);
  EXPECT_EQ(particles.size(), 500u + 3u * splits);
  // Mass to 1e-12 relative; momentum to 1e-10 of the sum of |m v|.
  EXPECT_LE(std::abs(particles.total_mass() - mass_before) / mass_before, 1e-12);
  EXPECT_LE((particles.total_momentum() - momentum_before).norm() / scale, 1e-10);
}

}  // namespace
}  // namespace talus
