// Tests of the 4 -> 1 fusion of calm, compact, round groups (paper 4.2, fig. 8b).
#include "talus/mudflow/particle_fusion.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "adaptivity_fixtures.hpp"
#include "talus/mudflow/particle_fission.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus {
namespace {

using adaptivity_fixtures::binned;
using adaptivity_fixtures::plane_ground;
using adaptivity_fixtures::radius_of_spacing;

double spacing_of(const ParticleSet& particles, std::size_t i) { return particles.radius[i] / kSupportPerSpacing; }

// Areal density (kg/m2) of every particle by the symmetrised SPH sum, and a uniform pressure (Pa).
void set_uniform_fields(ParticleSet& particles, double pressure) {
  adaptivity_fixtures::set_sph_density(particles);
  for (std::size_t i = 0; i < particles.size(); ++i) particles.pressure[i] = pressure;
}

void add_on_ground(ParticleSet& particles, const GroundModel& ground, double mass, double x, double y,
                   const Eigen::Vector3d& velocity, double spacing) {
  particles.add(mass, {x, y, ground.elevation(x, y)}, velocity, radius_of_spacing(spacing));
}

// A columns x columns lattice of `spacing` (m), lower-left particle at (x0, y0), all moving at
// `velocity`, uniform pressure.
ParticleSet lattice(const GroundModel& ground, int columns, double spacing, double x0, double y0,
                    const Eigen::Vector3d& velocity) {
  ParticleSet particles;
  for (int row = 0; row < columns; ++row) {
    for (int col = 0; col < columns; ++col) {
      add_on_ground(particles, ground, 1800.0 * spacing * spacing, x0 + col * spacing, y0 + row * spacing, velocity,
                    spacing);
    }
  }
  set_uniform_fields(particles, 20000.0);
  return particles;
}

// Four particles of spacing 4 m at the corners of a square of side 4 m (a calm group unless a
// test changes it), centred on (101.1, -98.3).
constexpr double kSquareSpacing = 4.0;
ParticleSet square_group(const GroundModel& ground) {
  ParticleSet particles;
  const Eigen::Vector3d velocity(2.0, -1.0, 0.4);
  const double offsets[4][2] = {{-2.0, -2.0}, {2.0, -2.0}, {-2.0, 2.0}, {2.0, 2.0}};  // m
  for (const auto& offset : offsets) {
    add_on_ground(particles, ground, 28800.0, 101.1 + offset[0], -98.3 + offset[1], velocity, kSquareSpacing);
  }
  set_uniform_fields(particles, 20000.0);
  return particles;
}

double momentum_scale(const ParticleSet& particles) {
  double sum = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) sum += particles.mass[i] * particles.velocity(i).norm();
  return sum;
}

TEST(ParticleFusion, CalmSquareGroupMerges) {
  const GroundModel ground = plane_ground();
  ParticleSet particles = square_group(ground);
  particles.level = {2, 1, 3, 2};
  particles.still_time = {0.5, 0.2, 0.7, 0.3};
  const PairSearch search = binned(particles);
  ASSERT_EQ(merge_particles(particles, search, ground, FusionRule{}), 1u);
  ASSERT_EQ(particles.size(), 1u);
  // Mass exact sum; centre to 1e-12 m; z on the ground to 1e-12 m; twice the radius exactly;
  // velocity to 1e-12 m/s; smallest level and still time.
  EXPECT_EQ(particles.mass[0], 4 * 28800.0);
  EXPECT_NEAR(particles.x[0], 101.1, 1e-12);
  EXPECT_NEAR(particles.y[0], -98.3, 1e-12);
  EXPECT_NEAR(particles.z[0], ground.elevation(101.1, -98.3), 1e-12);
  EXPECT_EQ(particles.radius[0], radius_of_spacing(2 * kSquareSpacing));
  EXPECT_NEAR((particles.velocity(0) - Eigen::Vector3d(2.0, -1.0, 0.4)).norm(), 0.0, 1e-12);
  EXPECT_EQ(particles.level[0], 1);
  EXPECT_EQ(particles.still_time[0], 0.2);
  EXPECT_NEAR(particles.pressure[0], 20000.0, 1e-9);
}

TEST(ParticleFusion, GroupWithAFastMemberDoesNotMerge) {
  const GroundModel ground = plane_ground();
  ParticleSet particles = square_group(ground);
  // 1 m/s faster: 0.75 m/s from the group's mean, above speed_difference = 0.5 m/s.
  particles.vx[2] += 1.0;
  const PairSearch search = binned(particles);
  EXPECT_EQ(merge_particles(particles, search, ground, FusionRule{}), 0u);
  EXPECT_EQ(particles.size(), 4u);
  // 0.6 m/s faster: 0.45 m/s from the mean, within the rule: the same group merges.
  particles.vx[2] -= 0.4;
  EXPECT_EQ(merge_particles(particles, search, ground, FusionRule{}), 1u);
}

TEST(ParticleFusion, GroupWithAPressureContrastDoesNotMerge) {
  const GroundModel ground = plane_ground();
  ParticleSet particles = square_group(ground);
  particles.pressure[3] = 40000.0;  // Pa: a contrast of order 1 across the group
  const PairSearch search = binned(particles);
  ASSERT_GT(pressure_contrast(particles, search, 3), FusionRule{}.threshold);
  EXPECT_EQ(merge_particles(particles, search, ground, FusionRule{}), 0u);
  EXPECT_EQ(particles.size(), 4u);
}

// Crowded fusion (docs/mudflow.md section 8): the square group at 30 m/s in mud five times as
// dense as its spacing holds (natural smoothing radius 9.6 / sqrt(5) = 4.3 m, so the merged
// particle would sum over 8.6 m, within a crowded_radius of the members' R, 9.6 m).
FusionRule crowded_rule() {
  FusionRule rule;
  rule.crowded_radius = radius_of_spacing(kSquareSpacing);
  return rule;
}

// The group with member 2 faster by `faster` (m/s) along x.
ParticleSet fast_crowded_square(const GroundModel& ground, double faster) {
  ParticleSet particles = square_group(ground);
  for (std::size_t i = 0; i < 4; ++i) {
    particles.vx[i] = 30.0;
    particles.vy[i] = 0.0;
    particles.vz[i] = 0.0;
    particles.density[i] = 5.0 * particles.mass[i] / (kSquareSpacing * kSquareSpacing);
  }
  particles.vx[2] += faster;
  return particles;
}

TEST(ParticleFusion, CrowdedGroupMergesWithinATenthOfItsSpeed) {
  const GroundModel ground = plane_ground();
  // 5 m/s faster: 3.75 m/s from the mean of 31.25 m/s, beyond 0.1 x 31.25 m/s.
  ParticleSet particles = fast_crowded_square(ground, 5.0);
  EXPECT_EQ(merge_particles(particles, binned(particles), ground, crowded_rule()), 0u);
  // 4 m/s faster: 3 m/s from the mean of 31 m/s, within 0.1 x 31 = 3.1 m/s but not 0.5 m/s.
  particles = fast_crowded_square(ground, 4.0);
  EXPECT_EQ(merge_particles(particles, binned(particles), ground, FusionRule{}), 0u);  // crowded fusion off
  EXPECT_EQ(merge_particles(particles, binned(particles), ground, crowded_rule()), 1u);
  ASSERT_EQ(particles.size(), 1u);
  // Momentum kept: 31 m/s to 1e-12 m/s.
  EXPECT_NEAR(particles.vx[0], 31.0, 1e-12);
}

TEST(ParticleFusion, GroupAsDenseAsItsSpacingIsNotCrowded) {
  const GroundModel ground = plane_ground();
  ParticleSet particles = fast_crowded_square(ground, 4.0);
  // Twice as dense as its spacing: natural radius 9.6 / sqrt(2) = 6.8 m, merged 13.6 m > 9.6 m.
  for (std::size_t i = 0; i < 4; ++i) particles.density[i] *= 2.0 / 5.0;
  const PairSearch search = binned(particles);
  EXPECT_EQ(merge_particles(particles, search, ground, crowded_rule()), 0u);
}

// A crowded group merges with a pressure contrast between the calm threshold (0.1) and its own
// (0.25), and not above its own.
TEST(ParticleFusion, CrowdedGroupHasItsOwnContrastThreshold) {
  const GroundModel ground = plane_ground();
  ParticleSet particles = fast_crowded_square(ground, 0.0);
  particles.pressure[3] = 22000.0;  // Pa, against 20000 for the others
  const PairSearch search = binned(particles);
  double largest = 0;
  for (std::size_t i = 0; i < 4; ++i) largest = std::max(largest, pressure_contrast(particles, search, i));
  ASSERT_GT(largest, FusionRule{}.threshold);
  ASSERT_LT(largest, FusionRule{}.crowded_threshold);
  EXPECT_EQ(merge_particles(particles, search, ground, FusionRule{}), 0u);
  FusionRule strict = crowded_rule();
  strict.crowded_threshold = 0.9 * largest;
  EXPECT_EQ(merge_particles(particles, search, ground, strict), 0u);
  EXPECT_EQ(merge_particles(particles, search, ground, crowded_rule()), 1u);
}

TEST(ParticleFusion, LineOfFourDoesNotMerge) {
  const GroundModel ground = plane_ground();
  ParticleSet particles;
  for (int k = 0; k < 4; ++k) {
    add_on_ground(particles, ground, 28800.0, 90.0 + kSquareSpacing * k, -100.0, {1.0, 0.0, 0.0}, kSquareSpacing);
  }
  set_uniform_fields(particles, 20000.0);
  const PairSearch search = binned(particles);
  EXPECT_EQ(merge_particles(particles, search, ground, FusionRule{}), 0u);
  EXPECT_EQ(particles.size(), 4u);
}

TEST(ParticleFusion, MergedSizesNeverExceedTheLargestSpacing) {
  const GroundModel ground = plane_ground();
  {
    // Spacing 6 m: a merge would make 12 m > 10 m.
    ParticleSet particles = lattice(ground, 4, 6.0, 80.0, -120.0, {1.0, 0.0, 0.0});
    const PairSearch search = binned(particles);
    EXPECT_EQ(merge_particles(particles, search, ground, FusionRule{0.1, 0.5, 10.0}), 0u);
  }
  // A 16 x 16 lattice of 2.5 m merges to 5 m, then to 10 m, then stops (20 m > 10 m).
  ParticleSet particles = lattice(ground, 16, 2.5, 60.0, -140.0, {1.0, 0.5, 0.0});
  const double mass_before = particles.total_mass();
  std::size_t rounds = 0;
  for (;;) {
    const PairSearch search = binned(particles);
    if (merge_particles(particles, search, ground, FusionRule{0.1, 0.5, 10.0}) == 0) break;
    set_uniform_fields(particles, 20000.0);
    ++rounds;
  }
  EXPECT_EQ(rounds, 2u);
  EXPECT_EQ(particles.size(), 16u);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    // Every spacing at most 10 m (to 1e-12 m).
    EXPECT_LE(spacing_of(particles, i), 10.0 + 1e-12);
  }
  // Mass to 1e-12 relative through two rounds.
  EXPECT_LE(std::abs(particles.total_mass() - mass_before) / mass_before, 1e-12);
}

TEST(ParticleFusion, MergeConservesMassAndMomentum) {
  const GroundModel ground = plane_ground();
  std::mt19937_64 random(77031);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05), spread(-0.15, 0.15), unit(0.0, 1.0);
  ParticleSet particles;
  const double spacing = 4.0;  // m
  for (int row = 0; row < 20; ++row) {
    for (int col = 0; col < 20; ++col) {
      const double x = 60.0 + spacing * (col + jitter(random)), y = -150.0 + spacing * (row + jitter(random));
      const Eigen::Vector3d velocity(3.0 + spread(random), -1.0 + spread(random), 0.5 + spread(random));
      add_on_ground(particles, ground, 28800.0 * (0.9 + 0.2 * unit(random)), x, y, velocity, spacing);
    }
  }
  set_uniform_fields(particles, 20000.0);
  const double mass_before = particles.total_mass();
  const Eigen::Vector3d momentum_before = particles.total_momentum();
  const double scale = momentum_scale(particles);
  const PairSearch search = binned(particles);

  const std::size_t merges = merge_particles(particles, search, ground, FusionRule{});
  // The jittered calm lattice merges mostly in squares.
  EXPECT_GT(merges, 50u);
  EXPECT_EQ(particles.size(), 400u - 3u * merges);
  // Mass to 1e-12 relative; momentum to 1e-10 of the sum of |m v|.
  EXPECT_LE(std::abs(particles.total_mass() - mass_before) / mass_before, 1e-12);
  EXPECT_LE((particles.total_momentum() - momentum_before).norm() / scale, 1e-10);
}

TEST(ParticleFusion, SplitThenMergeRestoresAnIsolatedParticle) {
  const GroundModel ground = plane_ground();
  ParticleSet particles;
  const double x = 100.3, y = -87.7, spacing = 8.0;
  const Eigen::Vector3d velocity(1.5, -0.7, 0.2);
  add_on_ground(particles, ground, 5000.0, x, y, velocity, spacing);
  set_uniform_fields(particles, 15000.0);
  const ParticleSet before = particles;

  // A negative threshold splits every particle (an isolated one has contrast 0).
  ASSERT_EQ(split_particles(particles, binned(particles), ground, FissionRule{-1.0, 1.0}), 1u);
  ASSERT_EQ(particles.size(), 4u);
  ASSERT_EQ(merge_particles(particles, binned(particles), ground, FusionRule{0.1, 0.5, 8.0}), 1u);
  ASSERT_EQ(particles.size(), 1u);
  // Mass to 1e-12 relative, position to 1e-12 m, velocity to 1e-12 m/s, radius exactly.
  EXPECT_LE(std::abs(particles.mass[0] - before.mass[0]) / before.mass[0], 1e-12);
  EXPECT_NEAR(particles.x[0], x, 1e-12);
  EXPECT_NEAR(particles.y[0], y, 1e-12);
  EXPECT_NEAR(particles.z[0], before.z[0], 1e-12);
  EXPECT_NEAR((particles.velocity(0) - velocity).norm(), 0.0, 1e-12);
  EXPECT_EQ(particles.radius[0], before.radius[0]);
}

}  // namespace
}  // namespace talus
