// The bilinear ground model of paper 2.2: elevation and material parameters known at the DEM
// nodes (cell centres) and interpolated bilinearly inside each square of four nodes.
#include "talus/ground/ground_model.hpp"

#include <utility>

namespace talus {
namespace {

// True unless the four node values are equal (==, so a NaN node always differs).
bool differ(double v00, double v10, double v01, double v11) { return !(v00 == v10 && v00 == v01 && v00 == v11); }

}  // namespace

GroundMaterial GroundMaterial::from(const LithologyClass& lithology, double vegetation_deperdition) {
  GroundMaterial material;
  material.elastic_slope = lithology.elastic_slope;
  material.yield_pressure = lithology.yield_pressure;
  material.plastic_slope = lithology.plastic_slope;
  material.unloading_slope = lithology.unloading_slope;
  material.friction = lithology.friction;
  material.rolling_friction = lithology.rolling_friction;
  material.restitution_normal = lithology.restitution_normal;
  material.restitution_tangential = lithology.restitution_tangential;
  material.noise_amplitude = lithology.noise_amplitude;
  material.vegetation_deperdition = vegetation_deperdition;
  return material;
}

// Paper 2.2, fig. 3a: one pass over the squares of four nodes, recording which values differ
// between the nodes and whether all four are valid.
GroundModel::GroundModel(Grid<double> elevation, Grid<GroundMaterial> node_materials)
    : elevation_(std::move(elevation)),
      materials_(std::move(node_materials)),
      x0_(elevation_.spec().geotransform[0]),
      y0_(elevation_.spec().geotransform[3]),
      inverse_dx_(1.0 / elevation_.spec().geotransform[1]),
      inverse_dy_(1.0 / elevation_.spec().geotransform[5]),
      col_offset_(elevation_.spec().col_offset),
      row_offset_(elevation_.spec().row_offset),
      last_col_(elevation_.spec().width - 1.0),
      last_row_(elevation_.spec().height - 1.0),
      last_col_square_(elevation_.spec().width > 1 ? elevation_.spec().width - 2 : 0),
      last_row_square_(elevation_.spec().height > 1 ? elevation_.spec().height - 2 : 0),
      width_(static_cast<std::size_t>(elevation_.spec().width)),
      step_x_(elevation_.spec().width > 1 ? 1 : 0),
      step_y_(elevation_.spec().height > 1 ? width_ : 0),
      square_flags_(elevation_.spec().cell_count(), 0) {
  require_same_grid(elevation_.spec(), materials_.spec(), "ground model: elevation and materials");
  const int width = spec().width, height = spec().height;
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      // The last row and column are a square's lower-left node only on a grid one node wide or
      // high, where the square's nodes coincide.
      const std::size_t i00 = static_cast<std::size_t>(row) * width_ + static_cast<std::size_t>(col);
      const std::size_t i10 = col + 1 < width ? i00 + 1 : i00;
      const std::size_t i01 = row + 1 < height ? i00 + width_ : i00;
      const std::size_t i11 = col + 1 < width ? i01 + 1 : i01;
      unsigned flags = 0;
      for (std::size_t k = 0; k < kFields.size(); ++k) {
        const auto field = kFields[k];
        if (differ(materials_[i00].*field, materials_[i10].*field, materials_[i01].*field, materials_[i11].*field)) {
          flags |= field_bit(k);
        }
      }
      if (differ(elevation_[i00], elevation_[i10], elevation_[i01], elevation_[i11])) flags |= kElevationDiffers;
      if (elevation_.is_valid(i00) && elevation_.is_valid(i10) && elevation_.is_valid(i01) && elevation_.is_valid(i11)) {
        flags |= kValidSquare;
      }
      square_flags_[i00] = static_cast<std::uint16_t>(flags);
    }
  }
}

Eigen::Vector3d GroundModel::normal(double x, double y) const {
  const Eigen::Vector2d gradient = slope(x, y);
  return Eigen::Vector3d(-gradient.x(), -gradient.y(), 1.0).normalized();
}

// One field blended as material() blends it (paper 2.2).
double GroundModel::material_field(double GroundMaterial::*field, const NodeSquare& s) const {
  const double v00 = materials_[s.i00].*field;
  if (!differ(v00, materials_[s.i10].*field, materials_[s.i01].*field, materials_[s.i11].*field)) return v00;
  return blend(v00, materials_[s.i10].*field, materials_[s.i01].*field, materials_[s.i11].*field, s);
}

}  // namespace talus
