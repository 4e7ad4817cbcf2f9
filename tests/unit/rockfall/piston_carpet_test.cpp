// Tests of the piston carpet of paper 2.2 (rockfall/piston_carpet): pistons on a plane, the
// window's exact lattice points, scrolling that keeps the state of pistons that stay and returns
// the energy of those that leave, a cost that depends on the window's moves and not on the DEM,
// a scrolled carpet equal bit for bit to one built over the final region, and invalid pistons
// outside the DEM and at nodata.
#include "talus/rockfall/piston_carpet.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "talus/core/errors.hpp"
#include "../../validation/synthetic_ground.hpp"

namespace talus {
namespace {

// A soil with a full stress cycle (the built-in "talus" class) and the given friction and
// vegetation deperdition (1/m).
GroundMaterial soil(double friction, double deperdition, double noise_amplitude = 0.0) {
  GroundMaterial material = testing_ground::fast_material(0.4, 0.7, friction, deperdition, noise_amplitude);
  material.elastic_slope = 1.0e8;
  material.yield_pressure = 8.0e5;
  material.plastic_slope = 7.0e7;
  material.unloading_slope = 1.9e8;
  return material;
}

// The plane z = 50 + 0.3 x - 0.2 y (m) on a width x height grid of 1 m cells.
GroundModel plane(int width, int height) {
  return testing_ground::make_ground(
      testing_ground::local_spec(width, height, 1.0), [](double x, double y) { return 50.0 + 0.3 * x - 0.2 * y; },
      soil(0.4, 0.007));
}

// A 24 x 20 grid of 2 m cells, rough elevations and two soils (noise amplitudes 0.3 m and 0).
GroundModel rough_model() {
  const GridSpec spec = testing_ground::local_spec(24, 20, 2.0);
  Grid<double> z(spec);
  Grid<GroundMaterial> materials(spec);
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) {
      z.at(col, row) = 100.0 + 3.0 * std::sin(0.9 * col + 0.4 * row * row) - 2.0 * col;
      materials.at(col, row) = col < 12 ? soil(0.5, 0.01, 0.3) : soil(0.3, 0.0, 0.0);
    }
  }
  return GroundModel(std::move(z), std::move(materials));
}

PerlinNoise unit_noise() {
  PerlinParameters parameters;
  parameters.base_frequency = 0.8;
  parameters.amplitude = 1.0;
  parameters.octaves = 3;
  parameters.seed = 11;
  return PerlinNoise(parameters);
}

bool same_state(const PistonState& a, const PistonState& b) {
  return a.compression == b.compression && a.max_compression == b.max_compression && a.max_pressure == b.max_pressure;
}

// Everything a piston is built from the ground with, compared exactly (NaN heights of invalid
// pistons compare equal).
void expect_same_piston(const Piston& a, const Piston& b) {
  EXPECT_EQ(a.i, b.i);
  EXPECT_EQ(a.j, b.j);
  EXPECT_EQ(a.valid, b.valid);
  EXPECT_EQ(a.rest_top.x(), b.rest_top.x());
  EXPECT_EQ(a.rest_top.y(), b.rest_top.y());
  if (a.valid) {
    EXPECT_EQ(a.rest_top.z(), b.rest_top.z());
  }
  EXPECT_EQ(a.axis, b.axis);
  EXPECT_EQ(a.area, b.area);
  EXPECT_EQ(a.cycle.elastic_slope, b.cycle.elastic_slope);
  EXPECT_EQ(a.cycle.yield_pressure, b.cycle.yield_pressure);
  EXPECT_EQ(a.cycle.plastic_slope, b.cycle.plastic_slope);
  EXPECT_EQ(a.cycle.unloading_slope, b.cycle.unloading_slope);
  EXPECT_EQ(a.friction, b.friction);
  EXPECT_EQ(a.vegetation_deperdition, b.vegetation_deperdition);
}

// On a plane: rest tops on the plane (1e-12 m: rounding of the bilinear blend), axes the plane's
// normal and cross-sections s^2 / n_z (relative 1e-12), the material's cycle, friction and
// vegetation (relative 1e-12: a blend of four equal values), fresh states.
TEST(PistonCarpet, PistonsOnAPlaneStandAlongItsNormal) {
  const GroundModel model = plane(30, 30);
  const PerturbedGround ground(model, nullptr);
  PistonCarpet carpet(ground, 0.25);
  EXPECT_EQ(carpet.cover(5.1, 8.9, -12.3, -9.05), 0.0);
  // x: 5.25 .. 8.75 (i = 21 .. 35); y: -12.25 .. -9.25 (j = -49 .. -37).
  EXPECT_EQ(carpet.window().i_begin, 21);
  EXPECT_EQ(carpet.window().i_end, 36);
  EXPECT_EQ(carpet.window().j_begin, -49);
  EXPECT_EQ(carpet.window().j_end, -36);
  ASSERT_EQ(carpet.size(), 15u * 13u);
  EXPECT_EQ(carpet.pistons_built(), 15u * 13u);

  const Eigen::Vector3d normal = Eigen::Vector3d(-0.3, 0.2, 1.0).normalized();
  const double area = 0.0625 / normal.z();
  const GroundMaterial material = soil(0.4, 0.007);
  for (const Piston& piston : carpet.pistons()) {
    SCOPED_TRACE(::testing::Message() << "piston " << piston.i << ", " << piston.j);
    ASSERT_TRUE(piston.valid);
    EXPECT_EQ(piston.rest_top.x(), 0.25 * static_cast<double>(piston.i));
    EXPECT_EQ(piston.rest_top.y(), 0.25 * static_cast<double>(piston.j));
    EXPECT_NEAR(piston.rest_top.z(), 50.0 + 0.3 * piston.rest_top.x() - 0.2 * piston.rest_top.y(), 1e-12);
    EXPECT_NEAR((piston.axis - normal).norm(), 0.0, 1e-12);
    EXPECT_NEAR(piston.area, area, 1e-12 * area);
    EXPECT_NEAR(piston.cycle.elastic_slope, material.elastic_slope, 1e-12 * material.elastic_slope);
    EXPECT_NEAR(piston.cycle.yield_pressure, material.yield_pressure, 1e-12 * material.yield_pressure);
    EXPECT_NEAR(piston.cycle.plastic_slope, material.plastic_slope, 1e-12 * material.plastic_slope);
    EXPECT_NEAR(piston.cycle.unloading_slope, material.unloading_slope, 1e-12 * material.unloading_slope);
    EXPECT_NEAR(piston.friction, 0.4, 1e-12);
    EXPECT_NEAR(piston.vegetation_deperdition, 0.007, 1e-12);
    EXPECT_TRUE(same_state(piston.state, PistonState{}));
    EXPECT_EQ(piston.top(), piston.rest_top);
    EXPECT_EQ(&carpet.at(piston.i, piston.j), &piston);
  }
}

// The window holds exactly the lattice points whose coordinates lie in the closed rectangle, even
// where k s rounds across a bound (3 x 0.1 = 0.30000000000000004 > 0.3, 7 x 0.1 > 0.7); bounds
// on the lattice are included; inverted or non-finite rectangles, and rectangles between
// lattice points, give an empty carpet.
TEST(PistonCarpet, WindowHoldsExactlyTheLatticePointsInTheClosedRectangle) {
  const GroundModel model = plane(10, 10);
  const PerturbedGround ground(model, nullptr);
  const auto check = [&ground](double spacing, double x_min, double x_max, double y_min, double y_max) {
    PistonCarpet carpet(ground, spacing);
    carpet.cover(x_min, x_max, y_min, y_max);
    const CarpetWindow& w = carpet.window();
    ASSERT_FALSE(w.empty());
    const auto x = [spacing](std::int64_t i) { return static_cast<double>(i) * spacing; };
    EXPECT_LT(x(w.i_begin - 1), x_min);
    EXPECT_GE(x(w.i_begin), x_min);
    EXPECT_LE(x(w.i_end - 1), x_max);
    EXPECT_GT(x(w.i_end), x_max);
    EXPECT_LT(x(w.j_begin - 1), y_min);
    EXPECT_GE(x(w.j_begin), y_min);
    EXPECT_LE(x(w.j_end - 1), y_max);
    EXPECT_GT(x(w.j_end), y_max);
    EXPECT_EQ(carpet.size(), static_cast<std::size_t>(w.columns() * w.rows()));
  };
  check(0.1, 0.3, 0.7, -0.7, -0.3);
  check(0.25, 1.0, 2.0, -2.0, -1.0);
  check(0.3, 0.0, 0.0, -0.6, -0.6);
  check(0.07, 1.234, 5.678, -6.5, -0.01);

  PistonCarpet exact(ground, 0.25);
  exact.cover(1.0, 2.0, -2.0, -1.0);
  EXPECT_EQ(exact.window().i_begin, 4);
  EXPECT_EQ(exact.window().i_end, 9);
  EXPECT_EQ(exact.window().j_begin, -8);
  EXPECT_EQ(exact.window().j_end, -3);

  exact.cover(2.0, 1.0, -2.0, -1.0);
  EXPECT_EQ(exact.size(), 0u);
  EXPECT_TRUE(exact.window().empty());
  exact.cover(1.0, 2.0, -2.0, std::nan(""));
  EXPECT_EQ(exact.size(), 0u);
  exact.cover(1.0, 2.0, -2.0, std::numeric_limits<double>::infinity());
  EXPECT_EQ(exact.size(), 0u);
  exact.cover(1.1, 1.2, -2.0, -1.0);  // between two lattice columns
  EXPECT_EQ(exact.size(), 0u);
  PistonCarpet rounded(ground, 0.3);
  rounded.cover(0.0, 0.0, -0.9, -0.9);  // -3 x 0.3 = -0.8999999999999999: not on the bound
  EXPECT_EQ(rounded.size(), 0u);
}

// Scrolling by 3 columns and 2 rows: pistons that stay keep their state bit for bit (and their
// ground data), new ones are fresh, and cover() returns the elastic energy, stored energy x
// area, of the compressed pistons that left (relative 1e-12: the same terms, summed in another
// order). Only the new pistons are built.
TEST(PistonCarpet, ScrollingKeepsStatesAndReturnsTheEnergyOfDroppedPistons) {
  const GroundModel model = rough_model();
  const PerlinNoise noise = unit_noise();
  const PerturbedGround ground(model, &noise);
  PistonCarpet carpet(ground, 0.25);
  carpet.cover(10.0, 12.0, -16.0, -14.0);  // i = 40 .. 48, j = -64 .. -56
  ASSERT_EQ(carpet.size(), 81u);

  // Varied histories: loaded past yield, partly unloaded, released to the footprint, untouched.
  for (Piston& piston : carpet.pistons()) {
    const std::int64_t kind = ((piston.i + 2 * piston.j) % 4 + 4) % 4;
    const double depth = 0.002 + 0.001 * static_cast<double>((piston.i * 7 + piston.j * 3) % 11 + 11) / 2.0;
    if (kind == 0) continue;
    press(piston.cycle, piston.state, depth);
    if (kind == 2) press(piston.cycle, piston.state, 0.8 * depth);
    if (kind == 3) press(piston.cycle, piston.state, 0.0);
  }
  const std::vector<Piston> before = carpet.pistons();

  // New region: x 10.75 .. 12.75 (i = 43 .. 51), y -16.5 .. -14.5 (j = -66 .. -58).
  const auto stays = [](const Piston& p) { return p.i >= 43 && p.i <= 51 && p.j >= -66 && p.j <= -58; };
  double expected_energy = 0.0;
  int compressed_leaving = 0;
  for (const Piston& piston : before) {
    if (stays(piston)) continue;
    const double energy = stored_energy(piston.cycle, piston.state) * piston.area;
    expected_energy += energy;
    if (energy > 0.0) ++compressed_leaving;
  }
  ASSERT_GT(compressed_leaving, 5);

  const double dropped = carpet.cover(10.75, 12.75, -16.5, -14.5);
  EXPECT_GT(dropped, 0.0);
  EXPECT_NEAR(dropped, expected_energy, 1e-12 * expected_energy);
  ASSERT_EQ(carpet.size(), 81u);
  EXPECT_EQ(carpet.pistons_built(), 81u + (81u - 6u * 7u));

  std::map<std::pair<std::int64_t, std::int64_t>, Piston> old;
  for (const Piston& piston : before) old.emplace(std::make_pair(piston.i, piston.j), piston);
  int kept = 0, fresh = 0;
  for (const Piston& piston : carpet.pistons()) {
    SCOPED_TRACE(::testing::Message() << "piston " << piston.i << ", " << piston.j);
    const auto found = old.find({piston.i, piston.j});
    if (found != old.end()) {
      ++kept;
      expect_same_piston(piston, found->second);
      EXPECT_TRUE(same_state(piston.state, found->second.state));
    } else {
      ++fresh;
      EXPECT_TRUE(same_state(piston.state, PistonState{}));
    }
  }
  EXPECT_EQ(kept, 6 * 7);
  EXPECT_EQ(fresh, 81 - 6 * 7);

  // Covering the same region again changes nothing and drops nothing.
  const Piston* first = &carpet.pistons().front();
  EXPECT_EQ(carpet.cover(10.7, 12.8, -16.55, -14.45), 0.0);
  EXPECT_EQ(&carpet.pistons().front(), first);
  EXPECT_EQ(carpet.pistons_built(), 81u + (81u - 6u * 7u));
}

// A 2 m x 2 m region (9 x 9 pistons at 0.25 m) moved one column at a time, then diagonally, over
// a 40 x 40 and a 400 x 400 DEM: exactly the new column (9) or the new column and row (17) is
// built at each move, the same on both DEMs.
TEST(PistonCarpet, MovingTheRegionBuildsOnlyNewRowsAndColumnsWhateverTheDem) {
  const GroundModel small_model = plane(40, 40);
  const GroundModel large_model = plane(400, 400);
  std::vector<std::uint64_t> builds;
  for (const GroundModel* model : {&small_model, &large_model}) {
    const PerturbedGround ground(*model, nullptr);
    PistonCarpet carpet(ground, 0.25);
    carpet.cover(5.0, 7.0, -7.0, -5.0);
    ASSERT_EQ(carpet.pistons_built(), 81u);
    for (int step = 1; step <= 80; ++step) {
      const double x = 5.0 + 0.25 * step;
      carpet.cover(x, x + 2.0, -7.0, -5.0);
      ASSERT_EQ(carpet.pistons_built(), 81u + 9u * static_cast<std::uint64_t>(step));
      carpet.cover(x, x + 2.0, -7.0, -5.0);
      ASSERT_EQ(carpet.pistons_built(), 81u + 9u * static_cast<std::uint64_t>(step));
    }
    const std::uint64_t straight = carpet.pistons_built();
    for (int step = 1; step <= 40; ++step) {
      const double x = 25.0 - 0.25 * step;
      const double y = -7.0 - 0.25 * step;
      carpet.cover(x, x + 2.0, y, y + 2.0);
      ASSERT_EQ(carpet.pistons_built(), straight + 17u * static_cast<std::uint64_t>(step));
    }
    EXPECT_EQ(carpet.size(), 81u);
    builds.push_back(carpet.pistons_built());
  }
  EXPECT_EQ(builds[0], builds[1]);
}

// After a wandering path of regions (drifts, growth, shrinking, a jump that replaces every
// piston), the carpet equals, bit for bit, a carpet built directly over the final region.
TEST(PistonCarpet, ScrolledCarpetEqualsOneBuiltOverTheFinalRegion) {
  const GroundModel model = rough_model();
  const PerlinNoise noise = unit_noise();
  const PerturbedGround ground(model, &noise);
  PistonCarpet scrolled(ground, 0.2);
  double x = 3.05, y = -30.0, half = 0.9;
  for (int step = 0; step < 200; ++step) {
    x += 0.037 + 0.05 * std::sin(0.3 * step);
    y += 0.061 * std::cos(0.17 * step);
    half = 0.9 + 0.4 * std::sin(0.11 * step);
    if (step == 120) x += 7.5;  // a jump: nothing of the old window stays
    scrolled.cover(x - half, x + half, y - half, y + half);
  }
  PistonCarpet direct(ground, 0.2);
  direct.cover(x - half, x + half, y - half, y + half);

  EXPECT_EQ(scrolled.window().i_begin, direct.window().i_begin);
  EXPECT_EQ(scrolled.window().i_end, direct.window().i_end);
  EXPECT_EQ(scrolled.window().j_begin, direct.window().j_begin);
  EXPECT_EQ(scrolled.window().j_end, direct.window().j_end);
  ASSERT_EQ(scrolled.size(), direct.size());
  ASSERT_GT(direct.size(), 50u);
  for (const Piston& piston : direct.pistons()) {
    SCOPED_TRACE(::testing::Message() << "piston " << piston.i << ", " << piston.j);
    expect_same_piston(scrolled.at(piston.i, piston.j), piston);
  }
}

// Lattice points outside the DEM or in a square of nodes with nodata are invalid: NaN height,
// no cross-section, a zero cycle, so that pressing them gives no pressure; all other points are
// valid. The lattice point on the nodata node itself is invalid.
TEST(PistonCarpet, PointsOutsideTheDemOrInNodataAreInvalid) {
  const GridSpec spec = testing_ground::local_spec(12, 10, 1.0);
  Grid<double> z(spec, 20.0);
  z.at(5, 5) = spec.nodata;
  const GroundModel model(std::move(z), Grid<GroundMaterial>(spec, soil(0.4, 0.0)));
  const PerturbedGround ground(model, nullptr);
  PistonCarpet carpet(ground, 0.5);
  carpet.cover(-1.0, 12.0, -10.0, 1.0);
  int valid = 0, invalid = 0;
  for (Piston& piston : carpet.pistons()) {
    SCOPED_TRACE(::testing::Message() << "piston " << piston.i << ", " << piston.j);
    EXPECT_EQ(piston.valid, model.contains(piston.rest_top.x(), piston.rest_top.y()));
    if (piston.valid) {
      ++valid;
      EXPECT_NEAR(piston.rest_top.z(), 20.0, 1e-12);
      continue;
    }
    ++invalid;
    EXPECT_TRUE(std::isnan(piston.rest_top.z()));
    EXPECT_EQ(piston.area, 0.0);
    EXPECT_EQ(press(piston.cycle, piston.state, 0.01), 0.0);
  }
  EXPECT_GT(valid, 100);
  EXPECT_GT(invalid, 100);
  EXPECT_FALSE(carpet.at(10, -10).valid);  // the nodata node (5, -5)
  EXPECT_FALSE(carpet.at(-1, -4).valid);   // west of the DEM
  EXPECT_FALSE(carpet.at(4, 1).valid);     // north of the DEM
  EXPECT_TRUE(carpet.at(4, -4).valid);
}

TEST(PistonCarpet, AtOutsideTheWindowThrowsAndSpacingMustBePositive) {
  const GroundModel model = plane(10, 10);
  const PerturbedGround ground(model, nullptr);
  PistonCarpet carpet(ground, 0.5);
  carpet.cover(1.0, 2.0, -2.0, -1.0);  // i = 2 .. 4, j = -4 .. -2
  EXPECT_NO_THROW(carpet.at(2, -4));
  EXPECT_THROW(carpet.at(1, -4), std::out_of_range);
  EXPECT_THROW(carpet.at(5, -3), std::out_of_range);
  const PistonCarpet& view = carpet;
  EXPECT_THROW(view.at(3, -1), std::out_of_range);
  EXPECT_THROW(view.at(3, -5), std::out_of_range);
  EXPECT_THROW(PistonCarpet(ground, 0.0), InputError);
  EXPECT_THROW(PistonCarpet(ground, -1.0), InputError);
  EXPECT_THROW(PistonCarpet(ground, std::nan("")), InputError);
}

}  // namespace
}  // namespace talus
