// Tests of release_particles (issue 5, docs/architecture.md section 3 --release): released mass, the
// lattice and its jitter, seeds, release points and the valid area.
#include "talus/mudflow/release_particles.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "../../validation/synthetic_ground.hpp"
#include "talus/core/errors.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus {
namespace {

using testing_ground::fast_material;
using testing_ground::local_spec;
using testing_ground::make_ground;

GroundModel hill(const GridSpec& spec) {
  return make_ground(spec, [](double x, double y) { return 100 + 0.4 * x + 0.01 * x * y; },
                     fast_material(0.5, 0.8, 0.6));
}

ReleaseSet released_cells(const GridSpec& spec) {
  ReleaseSet release;
  release.depth = Grid<float>(spec, 0.0f);
  for (int row = 2; row < 6; ++row) {  // interior cells: every lattice place lies on the surface
    for (int col = 2; col < 7; ++col) release.depth.at(col, row) = 0.5f + 0.25f * static_cast<float>(col + row);
  }
  release.depth.at(9, 9) = 1.75f;
  return release;
}

TEST(ReleaseParticles, MassIsDensityTimesVolumeAndParticlesRestOnTheGround) {
  const GridSpec spec = local_spec(12, 12, 5.0);
  const GroundModel ground = hill(spec);
  const ReleaseSet release = released_cells(spec);
  for (const double spacing : {2.5, 1.7, 8.0}) {  // 2 x 2, 3 x 3 and 1 particle per cell
    ReleaseLayout layout;
    layout.spacing = spacing;
    layout.thickness = ReleaseThickness::vertical;  // depths as heights of vertical columns
    const ParticleSet particles = release_particles(ground, release, layout);
    const int n = std::max(1, static_cast<int>(std::lround(5.0 / spacing)));
    ASSERT_EQ(particles.size(), static_cast<std::size_t>(21 * n * n));
    const double expected = layout.mud_density * release.vertical_volume();  // kg
    EXPECT_NEAR(particles.total_mass(), expected, 1e-12 * expected) << "spacing " << spacing;
    for (std::size_t i = 0; i < particles.size(); ++i) {
      EXPECT_TRUE(ground.contains(particles.x[i], particles.y[i]));
      EXPECT_EQ(particles.z[i], ground.elevation(particles.x[i], particles.y[i]));
      EXPECT_EQ(particles.velocity(i).norm(), 0.0);
      EXPECT_NEAR(particles.radius[i], kSupportPerSpacing * 5.0 / n, 1e-12);
      EXPECT_EQ(particles.state[i], ParticleState::flowing);
    }
  }
}

TEST(ReleaseParticles, SameSeedSameParticlesAnotherSeedOtherPlaces) {
  const GridSpec spec = local_spec(12, 12, 5.0);
  const GroundModel ground = hill(spec);
  const ReleaseSet release = released_cells(spec);
  ReleaseLayout layout;
  const ParticleSet a = release_particles(ground, release, layout);
  const ParticleSet b = release_particles(ground, release, layout);
  layout.seed = 2;
  const ParticleSet c = release_particles(ground, release, layout);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), c.size());
  std::size_t moved = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.x[i], b.x[i]);
    EXPECT_EQ(a.y[i], b.y[i]);
    EXPECT_EQ(a.mass[i], b.mass[i]);
    moved += (a.x[i] != c.x[i] || a.y[i] != c.y[i]) ? 1 : 0;
  }
  EXPECT_EQ(moved, a.size());
  // Jitter 0.25: each place within 0.25 / 2 x 2.5 m of its lattice point at (k + 0.5) 2.5 m
  // from the cell's edge (cell 0 spans x in [-2.5, 2.5] m).
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double lattice_offset_x = std::fmod(a.x[i] + 2.5, 2.5) - 1.25;  // m from the lattice point
    EXPECT_LE(std::abs(lattice_offset_x), 0.3125 + 1e-12);
  }
}

TEST(ReleaseParticles, APointReleasesOneCellAroundIt) {
  const GridSpec spec = local_spec(12, 12, 5.0);
  const GroundModel ground = hill(spec);
  ReleaseSet release;
  release.depth = Grid<float>(spec, 0.0f);
  release.points.push_back({23.7, -31.2, 1.5, {}});
  release.points.push_back({10.0, -10.0, 0.0, {}});  // no depth: nothing
  ReleaseLayout layout;
  layout.thickness = ReleaseThickness::vertical;
  const ParticleSet particles = release_particles(ground, release, layout);
  ASSERT_EQ(particles.size(), 4u);
  const double expected = layout.mud_density * 1.5 * 25.0;  // kg
  EXPECT_NEAR(particles.total_mass(), expected, 1e-12 * expected);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    EXPECT_LT(std::abs(particles.x[i] - 23.7), 2.5);  // inside the 5 m square centred on the point
    EXPECT_LT(std::abs(particles.y[i] + 31.2), 2.5);
  }
}

TEST(ReleaseParticles, RectangularCellsAndCellsOutsideTheValidArea) {
  GridSpec spec = local_spec(10, 10, 1.0);
  spec.geotransform = {-2.0, 4.0, 0.0, 1.0, 0.0, -2.0};  // 4 m x 2 m cells
  Grid<double> z(spec, 50.0);
  z.at(6, 6) = spec.nodata;
  const GroundModel ground(std::move(z), Grid<GroundMaterial>(spec, fast_material(0.5, 0.8, 0.6)));
  ReleaseSet release;
  release.depth = Grid<float>(spec, 0.0f);
  release.depth.at(3, 3) = 2.0f;
  release.depth.at(6, 6) = 2.0f;  // invalid node: nothing
  ReleaseLayout layout;
  layout.spacing = 2.0;  // 2 x 1 places of 2 m x 2 m
  const ParticleSet particles = release_particles(ground, release, layout);
  ASSERT_EQ(particles.size(), 2u);
  EXPECT_NEAR(particles.total_mass(), layout.mud_density * 2.0 * 8.0, 1e-12 * layout.mud_density * 16.0);
  EXPECT_NEAR(particles.radius[0], kSupportPerSpacing * 2.0, 1e-12);
  EXPECT_NE(particles.x[0], particles.x[1]);
}

TEST(ReleaseParticles, ABorderCellKeepsItsMassOnTheSurface) {
  // Cell (0, 0) spans x in [-2.5, 2.5] m, y in [-2.5, 2.5] m; the surface starts at its node
  // (0, 0), so of its 2 x 2 places only the one at (1.25, -1.25) m (+- jitter) lies on it.
  const GridSpec spec = local_spec(6, 6, 5.0);
  const GroundModel ground = hill(spec);
  ReleaseSet release;
  release.depth = Grid<float>(spec, 0.0f);
  release.depth.at(0, 0) = 1.0f;
  ReleaseLayout layout;
  layout.thickness = ReleaseThickness::vertical;
  const ParticleSet particles = release_particles(ground, release, layout);
  ASSERT_EQ(particles.size(), 1u);
  EXPECT_TRUE(ground.contains(particles.x[0], particles.y[0]));
  EXPECT_NEAR(particles.total_mass(), layout.mud_density * 25.0, 1e-12 * layout.mud_density * 25.0);
}

// The thin-layer convention (docs/inputs.md, Release): a depth d normal to a plane of slope phi
// releases rho0 d A / cos(phi), the vertical column of the same mass being d / cos(phi) high.
TEST(ReleaseParticles, NormalThicknessReleasesDepthOverTheCosineOfTheSlope) {
  const GridSpec spec = local_spec(12, 12, 5.0);
  const double phi = 35.0 * std::numbers::pi / 180.0;
  Grid<double> z(spec, 0.0);
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) z.at(col, row) = 500.0 - std::tan(phi) * spec.node_x(col);
  }
  const GroundModel ground(std::move(z), Grid<GroundMaterial>(spec, fast_material(0.5, 0.8, 0.6)));
  const ReleaseSet release = released_cells(spec);
  ReleaseLayout layout;
  ASSERT_EQ(layout.thickness, ReleaseThickness::normal);  // the default
  const double normal = release_particles(ground, release, layout).total_mass();
  layout.thickness = ReleaseThickness::vertical;
  const double vertical = release_particles(ground, release, layout).total_mass();
  EXPECT_NEAR(vertical, layout.mud_density * release.vertical_volume(), 1e-12 * vertical);
  EXPECT_NEAR(normal, vertical / std::cos(phi), 1e-12 * normal);
  // release_volume gives the same volumes without making particles.
  EXPECT_NEAR(release_volume(ground, release, ReleaseThickness::vertical), vertical / layout.mud_density, 1e-9);
  EXPECT_NEAR(release_volume(ground, release, ReleaseThickness::normal), normal / layout.mud_density, 1e-9);
}

// [mud] release_thickness (docs/inputs.md): auto reads a raster of negative depths, the surface
// lowering of a DEM of difference, as vertical, and every other release as normal to the ground;
// normal and vertical are taken as given.
TEST(ReleaseParticles, TheThicknessChoiceReadsADemOfDifferenceAsVertical) {
  EXPECT_EQ(parse_release_thickness("auto"), ReleaseThicknessChoice::automatic);
  EXPECT_EQ(parse_release_thickness("normal"), ReleaseThicknessChoice::normal);
  EXPECT_EQ(parse_release_thickness("vertical"), ReleaseThicknessChoice::vertical);
  EXPECT_THROW(parse_release_thickness("slope"), InputError);
  ReleaseSet attributes;
  ReleaseSet lowering;
  lowering.depths_from_surface_lowering = true;
  EXPECT_EQ(thickness_for_release(ReleaseThicknessChoice::automatic, attributes), ReleaseThickness::normal);
  EXPECT_EQ(thickness_for_release(ReleaseThicknessChoice::automatic, lowering), ReleaseThickness::vertical);
  EXPECT_EQ(thickness_for_release(ReleaseThicknessChoice::normal, lowering), ReleaseThickness::normal);
  EXPECT_EQ(thickness_for_release(ReleaseThicknessChoice::vertical, attributes), ReleaseThickness::vertical);
}

TEST(ReleaseParticles, RefusesLayoutsOutOfRangeAndOtherGrids) {
  const GridSpec spec = local_spec(6, 6, 5.0);
  const GroundModel ground = hill(spec);
  ReleaseSet release;
  release.depth = Grid<float>(spec, 1.0f);
  ReleaseLayout layout;
  layout.spacing = 0;
  EXPECT_THROW(release_particles(ground, release, layout), InputError);
  layout = ReleaseLayout{};
  layout.jitter = 1.5;
  EXPECT_THROW(release_particles(ground, release, layout), InputError);
  release.depth = Grid<float>(local_spec(5, 6, 5.0), 1.0f);
  EXPECT_THROW(release_particles(ground, release, ReleaseLayout{}), GridMismatch);
}

TEST(ReleaseParticles, RefusesAReleaseOfMillionsOfParticles) {
  // 36 cells of 5 m at 1 cm spacing would be 36 x 500^2 = 9 million particles (limit 4 million):
  // a particle size typed in centimetres, refused before any particle is made.
  const GridSpec spec = local_spec(6, 6, 5.0);
  const GroundModel ground = hill(spec);
  ReleaseSet release;
  release.depth = Grid<float>(spec, 1.0f);
  ReleaseLayout layout;
  layout.spacing = 0.01;
  try {
    release_particles(ground, release, layout);
    FAIL() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("9000000 particles"), std::string::npos) << error.what();
  }
  layout.spacing = 0.05;  // at most 36 x 100^2 = 360,000 particles: accepted
  EXPECT_NO_THROW(release_particles(ground, release, layout));
}

}  // namespace
}  // namespace talus
