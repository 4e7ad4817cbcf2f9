// Tests of the ground model's per-square flags (paper 2.2, fig. 3a): the inline queries, which
// blend only the values that differ between a square's four nodes, equal the plain bilinear
// blend of the four nodes bit for bit (tolerance zero: a seed's layers must not depend on the
// flags), on squares of one material, of one lithology under varying vegetation, of several
// lithologies, with infinite yield pressures, flat patches, invalid nodes, points outside the
// node lattice and grids one node wide.
#include "talus/ground/ground_model.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

// A north-up UTM-like grid of 10 m x 12.5 m cells.
GridSpec spec_of(int width, int height) {
  GridSpec spec;
  spec.width = width;
  spec.height = height;
  spec.geotransform = {612000.0, 10.0, 0.0, 5102000.0, 0.0, -12.5};
  return spec;
}

// Three lithologies (one purely elastic: infinite yield pressure) in blocks, vegetation that
// changes every third column, so that squares of one material, of one lithology under two
// vegetations, and of several lithologies all occur.
GroundMaterial material_at(int col, int row) {
  const int lithology = (col / 4 + row / 3) % 3;
  GroundMaterial m;
  m.elastic_slope = 1e7 * (lithology + 1);
  m.yield_pressure = lithology == 2 ? std::numeric_limits<double>::infinity() : 2e5 * (lithology + 1);
  m.plastic_slope = 5e6 * (lithology + 1);
  m.unloading_slope = 4e7 * (lithology + 1);
  m.friction = 0.3 + 0.2 * lithology;
  m.restitution_normal = 0.25 + 0.1 * lithology;
  m.restitution_tangential = 0.55 + 0.1 * lithology;
  m.noise_amplitude = lithology == 1 ? 0.0 : 0.1 * (lithology + 1);
  m.vegetation_deperdition = 0.001 * ((col / 3) % 4);
  return m;
}

// Rough elevations with a flat patch of equal nodes, one nodata node and one NaN node.
GroundModel model_of(int width, int height) {
  const GridSpec spec = spec_of(width, height);
  Grid<double> z(spec);
  Grid<GroundMaterial> materials(spec);
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const bool flat = col >= 5 && col <= 7 && row <= 2;
      z.at(col, row) = flat ? 950.0 : 900.0 + 7.0 * std::sin(1.3 * col + 0.7 * row * row) + 3.0 * col * row;
      materials.at(col, row) = material_at(col, row);
    }
  }
  if (width > 9 && height > 6) {
    z.at(2, 4) = spec.nodata;
    z.at(9, 6) = std::numeric_limits<double>::quiet_NaN();
  }
  return GroundModel(std::move(z), std::move(materials));
}

// Points by irrational steps over the node lattice and one cell beyond it on every side, the
// nodes and node lines themselves, and a NaN point.
std::vector<Eigen::Vector2d> points_over(const GridSpec& spec) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 3000; ++i) {
    const double u = i * 0.6180339887 - std::floor(i * 0.6180339887);
    const double v = i * 0.4142135624 - std::floor(i * 0.4142135624);
    points.emplace_back(spec.node_x(-1.0 + (spec.width + 1.0) * u), spec.node_y(-1.0 + (spec.height + 1.0) * v));
  }
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) {
      points.emplace_back(spec.node_x(col), spec.node_y(row));
      points.emplace_back(spec.node_x(col + 0.5), spec.node_y(row));
      points.emplace_back(spec.node_x(col), spec.node_y(row + 0.5));
    }
  }
  points.emplace_back(std::numeric_limits<double>::quiet_NaN(), spec.node_y(1.5));
  return points;
}

std::uint64_t bits(double value) { return std::bit_cast<std::uint64_t>(value); }

// The reference: paper fig. 3a written plainly. The square's lower node is floor() of the
// continuous node coordinate clamped into the grid; four equal values give that value, others the
// weighted sum with weights (1-fx)(1-fy), fx(1-fy), (1-fx)fy, fx fy.
struct ReferenceSquare {
  int col0 = 0, row0 = 0, col1 = 0, row1 = 0;
  double fx = 0, fy = 0;
};
// Continuous node coordinates as GridSpec::col_of and row_of, with the divisions done as
// multiplications by the inverse cell size, as the model does them once.
double node_col(const GridSpec& spec, double x) { return (x - spec.geotransform[0]) * (1.0 / spec.geotransform[1]) - 0.5; }
double node_row(const GridSpec& spec, double y) { return (y - spec.geotransform[3]) * (1.0 / spec.geotransform[5]) - 0.5; }
ReferenceSquare reference_square(const GridSpec& spec, double x, double y) {
  const double col = node_col(spec, x), row = node_row(spec, y);
  const auto lower = [](double u, int count) {
    if (std::isnan(u)) return 0;
    return static_cast<int>(std::clamp(std::floor(u), 0.0, std::max(count - 2, 0) * 1.0));
  };
  ReferenceSquare s;
  s.col0 = lower(col, spec.width);
  s.row0 = lower(row, spec.height);
  s.col1 = std::min(s.col0 + 1, spec.width - 1);
  s.row1 = std::min(s.row0 + 1, spec.height - 1);
  s.fx = col - s.col0;
  s.fy = row - s.row0;
  return s;
}
template <typename T, typename Value>
double reference_blend(const Grid<T>& grid, const ReferenceSquare& s, Value value) {
  const double v00 = value(grid.at(s.col0, s.row0)), v10 = value(grid.at(s.col1, s.row0));
  const double v01 = value(grid.at(s.col0, s.row1)), v11 = value(grid.at(s.col1, s.row1));
  if (v00 == v10 && v00 == v01 && v00 == v11) return v00;
  return (1.0 - s.fy) * (1.0 - s.fx) * v00 + (1.0 - s.fy) * s.fx * v10 + s.fy * (1.0 - s.fx) * v01 + s.fy * s.fx * v11;
}

// Every query at every point, compared bit for bit; counts the points that lay inside.
void expect_plain_bilinear_blend(const GroundModel& model, int& inside) {
  const GridSpec& spec = model.spec();
  const Grid<double>& z = model.elevation_grid();
  const Grid<GroundMaterial>& materials = model.material_grid();
  inside = 0;
  for (const Eigen::Vector2d& p : points_over(spec)) {
    SCOPED_TRACE(::testing::Message() << "point " << p.x() << ", " << p.y());
    const ReferenceSquare r = reference_square(spec, p.x(), p.y());
    const double col = node_col(spec, p.x()), row = node_row(spec, p.y());
    const bool within = col >= 0.0 && col <= spec.width - 1.0 && row >= 0.0 && row <= spec.height - 1.0;
    const bool valid = z.is_valid(r.col0, r.row0) && z.is_valid(r.col1, r.row0) && z.is_valid(r.col0, r.row1) &&
                       z.is_valid(r.col1, r.row1);
    ASSERT_EQ(model.contains(p.x(), p.y()), within && valid);
    if (model.contains(p.x(), p.y())) ++inside;
    const NodeSquare s = model.locate(p.x(), p.y());
    ASSERT_EQ(s.i00, z.index(r.col0, r.row0));
    ASSERT_EQ(s.i11, z.index(r.col1, r.row1));
    ASSERT_EQ(bits(s.fx), bits(r.fx));
    ASSERT_EQ(bits(s.fy), bits(r.fy));
    EXPECT_EQ(bits(model.elevation(s)), bits(reference_blend(z, r, [](double v) { return v; })));
    const auto field = [&](double GroundMaterial::*f) {
      return bits(reference_blend(materials, r, [f](const GroundMaterial& m) { return m.*f; }));
    };
    EXPECT_EQ(bits(model.noise_amplitude(s)), field(&GroundMaterial::noise_amplitude));
    EXPECT_EQ(bits(model.material_field(&GroundMaterial::friction, s)), field(&GroundMaterial::friction));
    const GroundMaterial m = model.material(s);
    EXPECT_EQ(bits(m.elastic_slope), field(&GroundMaterial::elastic_slope));
    EXPECT_EQ(bits(m.yield_pressure), field(&GroundMaterial::yield_pressure));
    EXPECT_EQ(bits(m.plastic_slope), field(&GroundMaterial::plastic_slope));
    EXPECT_EQ(bits(m.unloading_slope), field(&GroundMaterial::unloading_slope));
    EXPECT_EQ(bits(m.friction), field(&GroundMaterial::friction));
    EXPECT_EQ(bits(m.restitution_normal), field(&GroundMaterial::restitution_normal));
    EXPECT_EQ(bits(m.restitution_tangential), field(&GroundMaterial::restitution_tangential));
    EXPECT_EQ(bits(m.noise_amplitude), field(&GroundMaterial::noise_amplitude));
    EXPECT_EQ(bits(m.vegetation_deperdition), field(&GroundMaterial::vegetation_deperdition));
  }
}

TEST(GroundModelSquares, EveryQueryIsThePlainBilinearBlendBitForBit) {
  const GroundModel model = model_of(13, 9);
  int inside = 0;
  expect_plain_bilinear_blend(model, inside);
  // Most points lie inside, some outside or next to the invalid nodes.
  EXPECT_GT(inside, 1500);
  EXPECT_LT(inside, 3000);
}

TEST(GroundModelSquares, SquaresOfEveryKindOccurInTheTestGround) {
  // The comparison above means something only if the ground mixes the cases it is meant to
  // cover: squares of one material, one lithology under two vegetations, and several lithologies.
  const GroundModel model = model_of(13, 9);
  int uniform = 0, vegetation_only = 0, lithologies = 0;
  for (int row = 0; row + 1 < 9; ++row) {
    for (int col = 0; col + 1 < 13; ++col) {
      const GroundMaterial a = material_at(col, row), b = material_at(col + 1, row + 1);
      const GroundMaterial c = material_at(col + 1, row), d = material_at(col, row + 1);
      const bool same_lithology = a.friction == b.friction && a.friction == c.friction && a.friction == d.friction;
      const bool same_vegetation = a.vegetation_deperdition == b.vegetation_deperdition &&
                                   a.vegetation_deperdition == c.vegetation_deperdition &&
                                   a.vegetation_deperdition == d.vegetation_deperdition;
      if (same_lithology && same_vegetation) ++uniform;
      if (same_lithology && !same_vegetation) ++vegetation_only;
      if (!same_lithology) ++lithologies;
    }
  }
  EXPECT_GT(uniform, 10);
  EXPECT_GT(vegetation_only, 10);
  EXPECT_GT(lithologies, 10);
}

TEST(GroundModelSquares, GridsOneNodeWideOrHighAreTheirLineOfNodes) {
  // The squares of a single line of nodes are that line: only points on it lie inside.
  for (const auto& [width, height] : {std::pair{1, 6}, std::pair{7, 1}, std::pair{1, 1}}) {
    int inside = 0;
    expect_plain_bilinear_blend(model_of(width, height), inside);
    EXPECT_GT(inside, 0) << width << " x " << height;
    EXPECT_LT(inside, 100) << width << " x " << height;
  }
}

}  // namespace
}  // namespace talus
