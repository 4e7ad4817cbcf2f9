// The bilinear ground model of paper 2.2: elevation and material parameters known at the DEM
// nodes (cell centres) and interpolated bilinearly inside each square of four nodes.
#include "talus/ground/ground_model.hpp"

#include <array>
#include <cmath>
#include <utility>

namespace talus {
namespace {

// The square of four nodes that holds a point, and the point's place inside it.
// Nodes (col0, row0), (col1, row0), (col0, row1), (col1, row1); fx, fy are the continuous
// node coordinates minus col0, row0: in [0, 1] inside the lattice, outside it otherwise.
struct NodeSquare {
  int col0 = 0, row0 = 0, col1 = 0, row1 = 0;
  double fx = 0, fy = 0;
};

// Lower node index along one axis: floor(u) kept within [0, count - 2], so that the last line
// of nodes belongs to the square before it and the four nodes always exist (NaN gives 0).
int lower_node(double u, int count) {
  const double last_square = static_cast<double>(count > 1 ? count - 2 : 0);
  double base = std::floor(u);
  if (!(base >= 0.0)) base = 0.0;
  if (base > last_square) base = last_square;
  return static_cast<int>(base);
}

NodeSquare locate(const GridSpec& spec, double x, double y) {
  const double col = spec.col_of(x);
  const double row = spec.row_of(y);
  NodeSquare square;
  square.col0 = lower_node(col, spec.width);
  square.row0 = lower_node(row, spec.height);
  square.col1 = spec.width > 1 ? square.col0 + 1 : square.col0;
  square.row1 = spec.height > 1 ? square.row0 + 1 : square.row0;
  square.fx = col - square.col0;
  square.fy = row - square.row0;
  return square;
}

// Bilinear blend of the four node values v00 (col0,row0), v10 (col1,row0), v01 (col0,row1),
// v11 (col1,row1) at (fx, fy): paper fig. 3a.
double bilinear(double v00, double v10, double v01, double v11, double fx, double fy) {
  return (1.0 - fy) * ((1.0 - fx) * v00 + fx * v10) + fy * ((1.0 - fx) * v01 + fx * v11);
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
    : elevation_(std::move(elevation)), materials_(std::move(node_materials)) {
  require_same_grid(elevation_.spec(), materials_.spec(), "ground model: elevation and materials");
}

bool GroundModel::contains(double x, double y) const {
  const GridSpec& grid = spec();
  const double col = grid.col_of(x);
  const double row = grid.row_of(y);
  // Written so that NaN coordinates fall outside.
  if (!(col >= 0.0 && col <= grid.width - 1.0 && row >= 0.0 && row <= grid.height - 1.0)) return false;
  const NodeSquare s = locate(grid, x, y);
  return elevation_.is_valid(s.col0, s.row0) && elevation_.is_valid(s.col1, s.row0) &&
         elevation_.is_valid(s.col0, s.row1) && elevation_.is_valid(s.col1, s.row1);
}

double GroundModel::elevation(double x, double y) const {
  const NodeSquare s = locate(spec(), x, y);
  return bilinear(elevation_.at(s.col0, s.row0), elevation_.at(s.col1, s.row0), elevation_.at(s.col0, s.row1),
                  elevation_.at(s.col1, s.row1), s.fx, s.fy);
}

// Exact derivative of the bilinear patch: d/dfx and d/dfy, then the chain rule through
// col_of and row_of (dfx/dx = 1/dx, dfy/dy = 1/geotransform[5], negative for north-up grids).
Eigen::Vector2d GroundModel::slope(double x, double y) const {
  const NodeSquare s = locate(spec(), x, y);
  const double z00 = elevation_.at(s.col0, s.row0);
  const double z10 = elevation_.at(s.col1, s.row0);
  const double z01 = elevation_.at(s.col0, s.row1);
  const double z11 = elevation_.at(s.col1, s.row1);
  const double dz_dfx = (1.0 - s.fy) * (z10 - z00) + s.fy * (z11 - z01);
  const double dz_dfy = (1.0 - s.fx) * (z01 - z00) + s.fx * (z11 - z10);
  return {dz_dfx / spec().geotransform[1], dz_dfy / spec().geotransform[5]};
}

Eigen::Vector3d GroundModel::normal(double x, double y) const {
  const Eigen::Vector2d gradient = slope(x, y);
  return Eigen::Vector3d(-gradient.x(), -gradient.y(), 1.0).normalized();
}

// One material field interpolated bilinearly (paper 2.2), for callers that need only it.
double GroundModel::material_field(double GroundMaterial::*field, double x, double y) const {
  const NodeSquare s = locate(spec(), x, y);
  return bilinear(materials_.at(s.col0, s.row0).*field, materials_.at(s.col1, s.row0).*field,
                  materials_.at(s.col0, s.row1).*field, materials_.at(s.col1, s.row1).*field, s.fx, s.fy);
}

GroundMaterial GroundModel::material(double x, double y) const {
  const NodeSquare s = locate(spec(), x, y);
  const GroundMaterial& m00 = materials_.at(s.col0, s.row0);
  const GroundMaterial& m10 = materials_.at(s.col1, s.row0);
  const GroundMaterial& m01 = materials_.at(s.col0, s.row1);
  const GroundMaterial& m11 = materials_.at(s.col1, s.row1);
  GroundMaterial blended;
  for (const auto field : kMaterialFields) {
    blended.*field = bilinear(m00.*field, m10.*field, m01.*field, m11.*field, s.fx, s.fy);
  }
  return blended;
}

}  // namespace talus
