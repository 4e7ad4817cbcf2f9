// The bilinear ground model of paper 2.2: elevation and every material parameter known at the
// DEM nodes (cell centres) and interpolated bilinearly between them.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "talus/core/grid.hpp"
#include "talus/ground/materials.hpp"

namespace talus {

// Material parameters at one point of the ground, interpolated from the nodes.
struct GroundMaterial {
  double elastic_slope = 0;          // Pa/m
  double yield_pressure = 0;         // Pa
  double plastic_slope = 0;          // Pa/m
  double unloading_slope = 0;        // Pa/m
  double friction = 0;               // -
  double rolling_friction = 0;       // -
  double restitution_normal = 0;     // -
  double restitution_tangential = 0; // -
  double noise_amplitude = 0;        // m
  double vegetation_deperdition = 0; // 1/m

  static GroundMaterial from(const LithologyClass& lithology, double vegetation_deperdition);
};

// The square of four DEM nodes that holds a point (paper 2.2, fig. 3a) and the point's place in
// it: one look-up that elevation, slope and material at that point share.
struct NodeSquare {
  std::size_t i00 = 0, i10 = 0, i01 = 0, i11 = 0;  // flat indices of nodes (col0,row0), (col1,row0), (col0,row1), (col1,row1)
  double fx = 0, fy = 0;                           // continuous node coordinates minus col0, row0
};

class GroundModel {
 public:
  // elevation (m, nodata outside the valid area) and node materials must share one grid.
  GroundModel(Grid<double> elevation, Grid<GroundMaterial> node_materials);

  const GridSpec& spec() const { return elevation_.spec(); }
  const Grid<double>& elevation_grid() const { return elevation_; }
  const Grid<GroundMaterial>& material_grid() const { return materials_; }

  // The queries below are inline: a trajectory asks for about a thousand of them. Each reads
  // its square's flags (built once in the constructor) so that it blends only the values that
  // differ between the four nodes; four equal values give that value exactly, also when it is
  // infinite (an infinite yield pressure: purely elastic ground).

  // True where (x, y) lies between four valid nodes, so the surface is defined there (NaN outside).
  bool contains(double x, double y) const {
    const double col = (x - x0_) * inverse_dx_ - 0.5 - col_offset_;
    const double row = (y - y0_) * inverse_dy_ - 0.5 - row_offset_;
    if (!(col >= 0.0 && col <= last_col_ && row >= 0.0 && row <= last_row_)) return false;
    const std::size_t i00 = static_cast<std::size_t>(lower_node(row, last_row_square_)) * width_ +
                            static_cast<std::size_t>(lower_node(col, last_col_square_));
    return (square_flags_[i00] & kValidSquare) != 0;
  }

  // Paper 2.2, fig. 3a: the square of four nodes holding (x, y) and the point's place in it
  // (continuous node coordinates: node (col, row) at integer values; the lower node is clamped
  // so that the last line of nodes belongs to the square before it).
  NodeSquare locate(double x, double y) const {
    const double col = (x - x0_) * inverse_dx_ - 0.5 - col_offset_;
    const double row = (y - y0_) * inverse_dy_ - 0.5 - row_offset_;
    const int col0 = lower_node(col, last_col_square_);
    const int row0 = lower_node(row, last_row_square_);
    NodeSquare square;
    square.i00 = static_cast<std::size_t>(row0) * width_ + static_cast<std::size_t>(col0);
    square.i10 = square.i00 + step_x_;
    square.i01 = square.i00 + step_y_;
    square.i11 = square.i01 + step_x_;
    square.fx = col - col0;
    square.fy = row - row0;
    return square;
  }

  // Bilinear elevation (m); only meaningful where contains().
  double elevation(const NodeSquare& s) const {
    if ((square_flags_[s.i00] & kElevationDiffers) == 0) return elevation_[s.i00];
    return blend(elevation_[s.i00], elevation_[s.i10], elevation_[s.i01], elevation_[s.i11], s);
  }
  double elevation(double x, double y) const { return elevation(locate(x, y)); }

  // Exact gradient (dz/dx, dz/dy) of the bilinear patch: d/dfx and d/dfy, then the chain rule
  // through the node coordinates (dfy/dy = 1/geotransform[5], negative for north-up grids).
  Eigen::Vector2d slope(const NodeSquare& s) const {
    const double z00 = elevation_[s.i00];
    const double z10 = elevation_[s.i10];
    const double z01 = elevation_[s.i01];
    const double z11 = elevation_[s.i11];
    const double dz_dfx = (1.0 - s.fy) * (z10 - z00) + s.fy * (z11 - z01);
    const double dz_dfy = (1.0 - s.fx) * (z01 - z00) + s.fx * (z11 - z10);
    return {dz_dfx * inverse_dx_, dz_dfy * inverse_dy_};
  }
  Eigen::Vector2d slope(double x, double y) const { return slope(locate(x, y)); }

  // Unit upward normal of the bilinear surface at (x, y).
  Eigen::Vector3d normal(double x, double y) const;

  // Paper 3.4's noise amplitude A (m), interpolated bilinearly (paper 2.2).
  double noise_amplitude(const NodeSquare& s) const {
    if ((square_flags_[s.i00] & field_bit(kNoiseAmplitudeField)) == 0) return materials_[s.i00].noise_amplitude;
    return blend(materials_[s.i00].noise_amplitude, materials_[s.i10].noise_amplitude,
                 materials_[s.i01].noise_amplitude, materials_[s.i11].noise_amplitude, s);
  }

  // Every material field interpolated bilinearly (paper 2.2): the first node's material with the
  // fields that differ between the four nodes blended.
  GroundMaterial material(const NodeSquare& s) const {
    GroundMaterial blended = materials_[s.i00];
    for (unsigned differing = square_flags_[s.i00] & kMaterialFieldBits; differing != 0; differing &= differing - 1) {
      const auto field = kFields[static_cast<std::size_t>(std::countr_zero(differing))];
      blended.*field = blend(materials_[s.i00].*field, materials_[s.i10].*field, materials_[s.i01].*field,
                             materials_[s.i11].*field, s);
    }
    return blended;
  }
  GroundMaterial material(double x, double y) const { return material(locate(x, y)); }

  // One field of material(), e.g. &GroundMaterial::friction, without the others.
  double material_field(double GroundMaterial::*field, const NodeSquare& square) const;
  double material_field(double GroundMaterial::*field, double x, double y) const {
    return material_field(field, locate(x, y));
  }

 private:
  // Every field of GroundMaterial; bit k of a square's flags stands for kFields[k].
  static constexpr std::array<double GroundMaterial::*, 10> kFields{
      &GroundMaterial::elastic_slope,      &GroundMaterial::yield_pressure,
      &GroundMaterial::plastic_slope,      &GroundMaterial::unloading_slope,
      &GroundMaterial::friction,           &GroundMaterial::rolling_friction,
      &GroundMaterial::restitution_normal, &GroundMaterial::restitution_tangential,
      &GroundMaterial::noise_amplitude,    &GroundMaterial::vegetation_deperdition};
  static_assert(sizeof(GroundMaterial) == kFields.size() * sizeof(double),
                "a GroundMaterial field is missing from kFields");
  static constexpr std::size_t kNoiseAmplitudeField = 8;
  static_assert(kFields[kNoiseAmplitudeField] == &GroundMaterial::noise_amplitude);
  static constexpr unsigned field_bit(std::size_t k) { return 1u << k; }
  static constexpr unsigned kMaterialFieldBits = (1u << kFields.size()) - 1u;
  static constexpr unsigned kElevationDiffers = 1u << kFields.size();
  static constexpr unsigned kValidSquare = 2u << kFields.size();

  // floor(u) kept within [0, last_square], NaN giving 0; truncation is floor for the
  // non-negative values left after the clamps.
  static int lower_node(double u, int last_square) {
    if (!(u >= 0.0)) return 0;
    if (u >= static_cast<double>(last_square)) return last_square;
    return static_cast<int>(u);
  }
  // Paper fig. 3a: the weighted sum of four node values v00 (col0,row0), v10 (col1,row0),
  // v01 (col0,row1), v11 (col1,row1) with weights (1-fx)(1-fy), fx(1-fy), (1-fx)fy, fx fy.
  static double blend(double v00, double v10, double v01, double v11, const NodeSquare& s) {
    return (1.0 - s.fy) * (1.0 - s.fx) * v00 + (1.0 - s.fy) * s.fx * v10 + s.fy * (1.0 - s.fx) * v01 +
           s.fy * s.fx * v11;
  }

  Grid<double> elevation_;
  Grid<GroundMaterial> materials_;
  double x0_, y0_;                      // m: geotransform[0], geotransform[3]
  double inverse_dx_, inverse_dy_;      // 1/m: 1 / geotransform[1], 1 / geotransform[5]
  double col_offset_, row_offset_;      // a tile's window (GridSpec): its first node on the whole grid
  double last_col_, last_row_;          // node coordinates of the last column and row
  int last_col_square_, last_row_square_;  // largest lower-left node of a square
  std::size_t width_;                   // nodes per row
  std::size_t step_x_, step_y_;         // flat index steps to the next column and row (0 on a single line)
  // Per square, by its lower-left node: bit k when kFields[k] differs between its four nodes,
  // kElevationDiffers when their elevations do, kValidSquare when all four are valid.
  std::vector<std::uint16_t> square_flags_;
};

}  // namespace talus
