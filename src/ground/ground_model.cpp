// The bilinear ground model of paper 2.2: elevation and material parameters known at the DEM
// nodes (cell centres) and interpolated bilinearly inside each square of four nodes.
#include "talus/ground/ground_model.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <utility>

namespace talus {
namespace {

// Lower node index along one axis: floor(u) kept within [0, count - 2], so that the last line
// of nodes belongs to the square before it and the four nodes always exist (NaN gives 0).
// Truncation is floor for the non-negative values left after the clamps, without a libm call.
int lower_node(double u, int count) {
  const int last_square = count > 1 ? count - 2 : 0;
  if (!(u >= 0.0)) return 0;
  if (u >= static_cast<double>(last_square)) return last_square;
  return static_cast<int>(u);
}

// Bilinear blend of the four node values v00 (col0,row0), v10 (col1,row0), v01 (col0,row1),
// v11 (col1,row1) at (fx, fy) (paper fig. 3a), as the weighted sum with weights (1-fx)(1-fy),
// fx(1-fy), (1-fx)fy, fx fy. Four equal values give that value exactly, also when it is
// infinite (an infinite yield pressure: purely elastic ground).
double bilinear(double v00, double v10, double v01, double v11, const NodeSquare& s) {
  if (v00 == v10 && v00 == v01 && v00 == v11) return v00;
  return (1.0 - s.fy) * (1.0 - s.fx) * v00 + (1.0 - s.fy) * s.fx * v10 + s.fy * (1.0 - s.fx) * v01 + s.fy * s.fx * v11;
}

// Every field of GroundMaterial, so that all of them are interpolated the same way.
constexpr std::array<double GroundMaterial::*, 9> kMaterialFields{
    &GroundMaterial::elastic_slope,      &GroundMaterial::yield_pressure,
    &GroundMaterial::plastic_slope,      &GroundMaterial::unloading_slope,
    &GroundMaterial::friction,           &GroundMaterial::restitution_normal,
    &GroundMaterial::restitution_tangential, &GroundMaterial::noise_amplitude,
    &GroundMaterial::vegetation_deperdition};
static_assert(sizeof(GroundMaterial) == kMaterialFields.size() * sizeof(double),
              "a GroundMaterial field is missing from kMaterialFields");

bool same_material(const GroundMaterial& a, const GroundMaterial& b) {
  for (const auto field : kMaterialFields) {
    if (!(a.*field == b.*field)) return false;
  }
  return true;
}

}  // namespace

GroundMaterial GroundMaterial::from(const LithologyClass& lithology, double vegetation_deperdition) {
  GroundMaterial material;
  material.elastic_slope = lithology.elastic_slope;
  material.yield_pressure = lithology.yield_pressure;
  material.plastic_slope = lithology.plastic_slope;
  material.unloading_slope = lithology.unloading_slope;
  material.friction = lithology.friction;
  material.restitution_normal = lithology.restitution_normal;
  material.restitution_tangential = lithology.restitution_tangential;
  material.noise_amplitude = lithology.noise_amplitude;
  material.vegetation_deperdition = vegetation_deperdition;
  return material;
}

GroundModel::GroundModel(Grid<double> elevation, Grid<GroundMaterial> node_materials)
    : elevation_(std::move(elevation)),
      materials_(std::move(node_materials)),
      square_flags_(elevation_.spec(), 0),
      inverse_dx_(1.0 / elevation_.spec().geotransform[1]),
      inverse_dy_(1.0 / elevation_.spec().geotransform[5]) {
  require_same_grid(elevation_.spec(), materials_.spec(), "ground model: elevation and materials");
  const GridSpec& grid = spec();
  for (int row = 0; row < grid.height; ++row) {
    for (int col = 0; col < grid.width; ++col) {
      // The last row and column are never a square's lower-left node (lower_node): their flags are
      // those of a degenerate square and are never read.
      const int col1 = std::min(col + 1, grid.width - 1);
      const int row1 = std::min(row + 1, grid.height - 1);
      const bool valid = elevation_.is_valid(col, row) && elevation_.is_valid(col1, row) &&
                         elevation_.is_valid(col, row1) && elevation_.is_valid(col1, row1);
      const GroundMaterial& m = materials_.at(col, row);
      const bool uniform = same_material(m, materials_.at(col1, row)) && same_material(m, materials_.at(col, row1)) &&
                           same_material(m, materials_.at(col1, row1));
      square_flags_.at(col, row) = static_cast<unsigned char>((valid ? kValidSquare : 0) | (uniform ? kUniformMaterial : 0));
    }
  }
}

// Continuous node coordinates of (x, y): node (col, row) at integer values (GridSpec::col_of and
// row_of, with the divisions done once in the constructor).
Eigen::Vector2d GroundModel::node_coordinates(double x, double y) const {
  const GridSpec& grid = spec();
  return {(x - grid.geotransform[0]) * inverse_dx_ - 0.5, (y - grid.geotransform[3]) * inverse_dy_ - 0.5};
}

NodeSquare GroundModel::locate(double x, double y) const {
  const GridSpec& grid = spec();
  const Eigen::Vector2d node = node_coordinates(x, y);
  const double col = node.x(), row = node.y();
  const int col0 = lower_node(col, grid.width);
  const int row0 = lower_node(row, grid.height);
  const std::size_t step_x = grid.width > 1 ? 1 : 0;
  const std::size_t step_y = grid.height > 1 ? static_cast<std::size_t>(grid.width) : 0;
  NodeSquare square;
  square.i00 = elevation_.index(col0, row0);
  square.i10 = square.i00 + step_x;
  square.i01 = square.i00 + step_y;
  square.i11 = square.i01 + step_x;
  square.fx = col - col0;
  square.fy = row - row0;
  return square;
}

bool GroundModel::contains(double x, double y) const {
  const GridSpec& grid = spec();
  const Eigen::Vector2d node = node_coordinates(x, y);
  const double col = node.x(), row = node.y();
  // Written so that NaN coordinates fall outside.
  if (!(col >= 0.0 && col <= grid.width - 1.0 && row >= 0.0 && row <= grid.height - 1.0)) return false;
  return (square_flags_.at(lower_node(col, grid.width), lower_node(row, grid.height)) & kValidSquare) != 0;
}

double GroundModel::elevation(double x, double y) const { return elevation(locate(x, y)); }

double GroundModel::elevation(const NodeSquare& s) const {
  return bilinear(elevation_[s.i00], elevation_[s.i10], elevation_[s.i01], elevation_[s.i11], s);
}

Eigen::Vector2d GroundModel::slope(double x, double y) const { return slope(locate(x, y)); }

// Exact derivative of the bilinear patch: d/dfx and d/dfy, then the chain rule through the
// node coordinates (dfx/dx = 1/dx, dfy/dy = 1/geotransform[5], negative for north-up grids).
Eigen::Vector2d GroundModel::slope(const NodeSquare& s) const {
  const double z00 = elevation_[s.i00];
  const double z10 = elevation_[s.i10];
  const double z01 = elevation_[s.i01];
  const double z11 = elevation_[s.i11];
  const double dz_dfx = (1.0 - s.fy) * (z10 - z00) + s.fy * (z11 - z01);
  const double dz_dfy = (1.0 - s.fx) * (z01 - z00) + s.fx * (z11 - z10);
  return {dz_dfx * inverse_dx_, dz_dfy * inverse_dy_};
}

Eigen::Vector3d GroundModel::normal(double x, double y) const {
  const Eigen::Vector2d gradient = slope(x, y);
  return Eigen::Vector3d(-gradient.x(), -gradient.y(), 1.0).normalized();
}

// One material field interpolated bilinearly (paper 2.2), for callers that need only it.
double GroundModel::material_field(double GroundMaterial::*field, double x, double y) const {
  return material_field(field, locate(x, y));
}

double GroundModel::material_field(double GroundMaterial::*field, const NodeSquare& s) const {
  return bilinear(materials_[s.i00].*field, materials_[s.i10].*field, materials_[s.i01].*field,
                  materials_[s.i11].*field, s);
}

GroundMaterial GroundModel::material(double x, double y) const { return material(locate(x, y)); }

// Every field blended as material_field() does (paper 2.2), read as arrays of doubles.
GroundMaterial GroundModel::material(const NodeSquare& s) const {
  if ((square_flags_[s.i00] & kUniformMaterial) != 0) return materials_[s.i00];
  using Fields = std::array<double, kMaterialFields.size()>;
  const auto m00 = std::bit_cast<Fields>(materials_[s.i00]);
  const auto m10 = std::bit_cast<Fields>(materials_[s.i10]);
  const auto m01 = std::bit_cast<Fields>(materials_[s.i01]);
  const auto m11 = std::bit_cast<Fields>(materials_[s.i11]);
  Fields blended;
  for (std::size_t k = 0; k < blended.size(); ++k) blended[k] = bilinear(m00[k], m10[k], m01[k], m11[k], s);
  return std::bit_cast<GroundMaterial>(blended);
}

}  // namespace talus
