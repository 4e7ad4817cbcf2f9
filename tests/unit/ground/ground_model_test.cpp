// Tests of the bilinear ground model (paper 2.2).
#include "talus/ground/ground_model.hpp"

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "talus/core/errors.hpp"

namespace talus {
namespace {

constexpr int kWidth = 6;
constexpr int kHeight = 5;

// A north-up UTM-like grid with non-square cells (10 m x 12.5 m).
GridSpec test_spec() {
  GridSpec spec;
  spec.width = kWidth;
  spec.height = kHeight;
  spec.geotransform = {612000.0, 10.0, 0.0, 5102000.0, 0.0, -12.5};
  spec.crs_wkt = "EPSG:32632";
  return spec;
}

// A point given by its continuous node coordinates (node (col, row) at integer values).
struct Point {
  double x, y;
};
Point at_node_coords(const GridSpec& spec, double col, double row) { return {spec.node_x(col), spec.node_y(row)}; }

// The plane z = 1200 + a (x - x0) + b (y - y0), written from node indices so that node values
// carry no rounding from the large UTM coordinates.
constexpr double kSlopeX = 0.3;
constexpr double kSlopeY = -0.45;
double plane_at_node(const GridSpec& spec, int col, int row) {
  return 1200.0 + kSlopeX * (col + 0.5) * spec.geotransform[1] + kSlopeY * (row + 0.5) * spec.geotransform[5];
}
double plane_at(const GridSpec& spec, double x, double y) {
  return 1200.0 + kSlopeX * (x - spec.geotransform[0]) + kSlopeY * (y - spec.geotransform[3]);
}

Grid<double> plane_grid(const GridSpec& spec) {
  Grid<double> grid(spec);
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) grid.at(col, row) = plane_at_node(spec, col, row);
  }
  return grid;
}

// Irregular node elevations (no plane, no symmetry).
Grid<double> rough_grid(const GridSpec& spec) {
  Grid<double> grid(spec);
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) {
      grid.at(col, row) = 900.0 + 7.0 * std::sin(1.3 * col + 0.7 * row * row) + 3.0 * col * row;
    }
  }
  return grid;
}

GroundModel model_with(Grid<double> elevation) {
  Grid<GroundMaterial> materials(elevation.spec());
  return GroundModel(std::move(elevation), std::move(materials));
}

// Points spread over the whole node lattice, its boundary lines included.
std::vector<Point> lattice_points(const GridSpec& spec) {
  std::vector<Point> points;
  const int steps = 37;
  for (int a = 0; a <= steps; ++a) {
    for (int b = 0; b <= steps; ++b) {
      const double col = (spec.width - 1.0) * a / steps;
      const double row = (spec.height - 1.0) * b / steps;
      points.push_back(at_node_coords(spec, col, row));
    }
  }
  return points;
}

TEST(GroundModel, ElevationIsExactAtEveryNode) {
  const GridSpec spec = test_spec();
  const Grid<double> nodes = rough_grid(spec);
  const GroundModel model = model_with(nodes);
  for (int row = 0; row < kHeight; ++row) {
    for (int col = 0; col < kWidth; ++col) {
      const Point p = at_node_coords(spec, col, row);
      EXPECT_NEAR(model.elevation(p.x, p.y), nodes.at(col, row), 1e-9) << "node " << col << "," << row;
    }
  }
}

TEST(GroundModel, ElevationIsTheBilinearBlendInsideASquare) {
  const GridSpec spec = test_spec();
  const Grid<double> nodes = rough_grid(spec);
  const GroundModel model = model_with(nodes);
  // At (col, row) = (2.25, 1.75): weights 0.75*0.25, 0.25*0.25, 0.75*0.75, 0.25*0.75.
  const Point p = at_node_coords(spec, 2.25, 1.75);
  const double expected = 0.1875 * nodes.at(2, 1) + 0.0625 * nodes.at(3, 1) + 0.5625 * nodes.at(2, 2) +
                          0.1875 * nodes.at(3, 2);
  EXPECT_NEAR(model.elevation(p.x, p.y), expected, 1e-9);
}

TEST(GroundModel, TiltedPlaneIsReproducedExactlyEverywhereInside) {
  const GridSpec spec = test_spec();
  const GroundModel model = model_with(plane_grid(spec));
  for (const Point& p : lattice_points(spec)) {
    ASSERT_TRUE(model.contains(p.x, p.y));
    EXPECT_NEAR(model.elevation(p.x, p.y), plane_at(spec, p.x, p.y), 1e-9) << p.x << "," << p.y;
  }
}

TEST(GroundModel, SlopeAndNormalOfAnInclinedPlaneAreExact) {
  const GridSpec spec = test_spec();
  const GroundModel model = model_with(plane_grid(spec));
  const double norm = std::sqrt(kSlopeX * kSlopeX + kSlopeY * kSlopeY + 1.0);
  for (const Point& p : lattice_points(spec)) {
    const Eigen::Vector2d slope = model.slope(p.x, p.y);
    EXPECT_NEAR(slope.x(), kSlopeX, 1e-12);
    EXPECT_NEAR(slope.y(), kSlopeY, 1e-12);
    const Eigen::Vector3d n = model.normal(p.x, p.y);
    EXPECT_NEAR(n.x(), -kSlopeX / norm, 1e-12);
    EXPECT_NEAR(n.y(), -kSlopeY / norm, 1e-12);
    EXPECT_NEAR(n.z(), 1.0 / norm, 1e-12);
  }
}

TEST(GroundModel, SlopeIsTheGradientOfTheBilinearPatch) {
  const GridSpec spec = test_spec();
  const GroundModel model = model_with(rough_grid(spec));
  // Interior points of several squares, away from the node lines where the slope jumps.
  for (double col : {0.3, 1.61, 2.5, 4.83}) {
    for (double row : {0.27, 1.5, 2.91, 3.4}) {
      const Point p = at_node_coords(spec, col, row);
      // The patch is linear along x and along y: a central difference is exact up to rounding.
      const double h = 1e-3;  // m
      const double x_plus = p.x + h, x_minus = p.x - h, y_plus = p.y + h, y_minus = p.y - h;
      const double dz_dx = (model.elevation(x_plus, p.y) - model.elevation(x_minus, p.y)) / (x_plus - x_minus);
      const double dz_dy = (model.elevation(p.x, y_plus) - model.elevation(p.x, y_minus)) / (y_plus - y_minus);
      const Eigen::Vector2d slope = model.slope(p.x, p.y);
      EXPECT_NEAR(slope.x(), dz_dx, 1e-8) << col << "," << row;
      EXPECT_NEAR(slope.y(), dz_dy, 1e-8) << col << "," << row;
      const Eigen::Vector3d n = model.normal(p.x, p.y);
      EXPECT_NEAR(n.norm(), 1.0, 1e-14);
      EXPECT_GT(n.z(), 0.0);
      EXPECT_NEAR(n.x() / n.z(), -slope.x(), 1e-12);
      EXPECT_NEAR(n.y() / n.z(), -slope.y(), 1e-12);
    }
  }
}

// Each field varies as its own bilinear function of the node coordinates, so its interpolation
// must reproduce that function exactly.
double field_value(int field, double col, double row) {
  return (field + 1.0) + (0.5 * field + 1.0) * col - (field - 3.0) * row + 0.25 * (field + 2.0) * col * row;
}

GroundMaterial material_at(double col, double row) {
  GroundMaterial m;
  m.elastic_slope = field_value(0, col, row);
  m.yield_pressure = field_value(1, col, row);
  m.plastic_slope = field_value(2, col, row);
  m.unloading_slope = field_value(3, col, row);
  m.friction = field_value(4, col, row);
  m.restitution_normal = field_value(5, col, row);
  m.restitution_tangential = field_value(6, col, row);
  m.noise_amplitude = field_value(7, col, row);
  m.vegetation_deperdition = field_value(8, col, row);
  return m;
}

TEST(GroundModel, EveryMaterialFieldIsInterpolatedBilinearly) {
  const GridSpec spec = test_spec();
  Grid<GroundMaterial> materials(spec);
  for (int row = 0; row < kHeight; ++row) {
    for (int col = 0; col < kWidth; ++col) materials.at(col, row) = material_at(col, row);
  }
  const GroundModel model(plane_grid(spec), materials);
  for (double col : {0.0, 0.4, 1.75, 3.5, 5.0}) {
    for (double row : {0.0, 0.6, 2.2, 3.95, 4.0}) {
      const Point p = at_node_coords(spec, col, row);
      const GroundMaterial got = model.material(p.x, p.y);
      const GroundMaterial want = material_at(col, row);
      EXPECT_NEAR(got.elastic_slope, want.elastic_slope, 1e-9);
      EXPECT_NEAR(got.yield_pressure, want.yield_pressure, 1e-9);
      EXPECT_NEAR(got.plastic_slope, want.plastic_slope, 1e-9);
      EXPECT_NEAR(got.unloading_slope, want.unloading_slope, 1e-9);
      EXPECT_NEAR(got.friction, want.friction, 1e-9);
      EXPECT_NEAR(got.restitution_normal, want.restitution_normal, 1e-9);
      EXPECT_NEAR(got.restitution_tangential, want.restitution_tangential, 1e-9);
      EXPECT_NEAR(got.noise_amplitude, want.noise_amplitude, 1e-9);
      EXPECT_NEAR(got.vegetation_deperdition, want.vegetation_deperdition, 1e-9);
    }
  }
}

TEST(GroundModel, OneNodesMaterialSpreadsWithBilinearWeights) {
  const GridSpec spec = test_spec();
  Grid<GroundMaterial> materials(spec);
  materials.at(3, 2).friction = 0.8;
  materials.at(3, 2).vegetation_deperdition = 0.02;
  const GroundModel model(plane_grid(spec), materials);
  // At (2.25, 1.75) node (3, 2) is the (col1, row1) corner: weight fx fy = 0.25 * 0.75.
  Point p = at_node_coords(spec, 2.25, 1.75);
  EXPECT_NEAR(model.material(p.x, p.y).friction, 0.8 * 0.25 * 0.75, 1e-15);
  EXPECT_NEAR(model.material(p.x, p.y).vegetation_deperdition, 0.02 * 0.25 * 0.75, 1e-15);
  // A square that does not touch node (3, 2).
  p = at_node_coords(spec, 0.5, 3.5);
  EXPECT_EQ(model.material(p.x, p.y).friction, 0.0);
}

TEST(GroundMaterial, FromCopiesLithologyAndVegetation) {
  LithologyClass rock;
  rock.elastic_slope = 1.0e7;
  rock.yield_pressure = 2.0e5;
  rock.plastic_slope = 3.0e6;
  rock.unloading_slope = 4.0e7;
  rock.friction = 0.6;
  rock.restitution_normal = 0.35;
  rock.restitution_tangential = 0.8;
  rock.noise_amplitude = 0.15;
  const GroundMaterial m = GroundMaterial::from(rock, 0.012);
  EXPECT_EQ(m.elastic_slope, 1.0e7);
  EXPECT_EQ(m.yield_pressure, 2.0e5);
  EXPECT_EQ(m.plastic_slope, 3.0e6);
  EXPECT_EQ(m.unloading_slope, 4.0e7);
  EXPECT_EQ(m.friction, 0.6);
  EXPECT_EQ(m.restitution_normal, 0.35);
  EXPECT_EQ(m.restitution_tangential, 0.8);
  EXPECT_EQ(m.noise_amplitude, 0.15);
  EXPECT_EQ(m.vegetation_deperdition, 0.012);
}

TEST(GroundModel, ContainsIsFalseAroundInvalidNodesAndOutsideTheLattice) {
  const GridSpec spec = test_spec();
  Grid<double> elevation = plane_grid(spec);
  elevation.at(2, 1) = spec.nodata;
  elevation.at(5, 4) = std::numeric_limits<double>::quiet_NaN();
  const GroundModel model = model_with(elevation);
  const auto inside = [&](double col, double row) {
    const Point p = at_node_coords(spec, col, row);
    return model.contains(p.x, p.y);
  };
  // The four squares around the nodata node (2, 1), and the node itself.
  EXPECT_FALSE(inside(1.5, 0.5));
  EXPECT_FALSE(inside(2.5, 0.5));
  EXPECT_FALSE(inside(1.5, 1.5));
  EXPECT_FALSE(inside(2.5, 1.5));
  EXPECT_FALSE(inside(2.0, 1.0));
  EXPECT_FALSE(inside(1.99, 1.01));
  // The square next to the NaN corner node (5, 4).
  EXPECT_FALSE(inside(4.5, 3.5));
  EXPECT_FALSE(inside(5.0, 4.0));
  // Squares made of four valid nodes, their edges and corner nodes included.
  EXPECT_TRUE(inside(0.5, 3.5));
  EXPECT_TRUE(inside(3.5, 2.5));
  EXPECT_TRUE(inside(0.0, 0.0));
  EXPECT_TRUE(inside(0.0, 4.0));
  EXPECT_TRUE(inside(5.0, 0.0));
  EXPECT_TRUE(inside(1.0, 2.5));
  // Outside the node lattice, even where still inside the raster's outer cells.
  EXPECT_FALSE(inside(-0.01, 2.5));
  EXPECT_FALSE(inside(2.5, -0.01));
  EXPECT_FALSE(inside(5.01, 2.5));
  EXPECT_FALSE(inside(0.5, 4.01));
  EXPECT_FALSE(inside(-20.0, 30.0));
  EXPECT_FALSE(model.contains(std::numeric_limits<double>::quiet_NaN(), spec.node_y(2.5)));
}

TEST(GroundModel, RefusesAMaterialGridOnAnotherGrid) {
  const GridSpec spec = test_spec();
  GridSpec narrower = spec;
  narrower.width = kWidth - 1;
  GridSpec shifted = spec;
  shifted.geotransform[0] += 5.0;
  GridSpec finer = spec;
  finer.geotransform[1] = 5.0;
  GridSpec other_crs = spec;
  other_crs.crs_wkt = "EPSG:2056";
  const auto build = [&](const GridSpec& materials_spec) {
    return GroundModel(plane_grid(spec), Grid<GroundMaterial>(materials_spec));
  };
  for (const GridSpec& other : {narrower, shifted, finer, other_crs}) EXPECT_THROW(build(other), GridMismatch);
  EXPECT_NO_THROW(build(spec));
}

}  // namespace
}  // namespace talus
