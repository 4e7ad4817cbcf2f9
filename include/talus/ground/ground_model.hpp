// The bilinear ground model of paper 2.2: elevation and every material parameter known at the
// DEM nodes (cell centres) and interpolated bilinearly between them.
#pragma once

#include <cstddef>

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

  // True where (x, y) lies between four valid nodes, so the surface is defined there.
  bool contains(double x, double y) const;
  // Bilinear elevation (m) at (x, y); only meaningful where contains(x, y).
  double elevation(double x, double y) const;
  // Gradient (dz/dx, dz/dy) of the bilinear surface at (x, y).
  Eigen::Vector2d slope(double x, double y) const;
  // Unit upward normal of the bilinear surface at (x, y).
  Eigen::Vector3d normal(double x, double y) const;
  // Material parameters interpolated bilinearly from the four surrounding nodes.
  GroundMaterial material(double x, double y) const;
  // One field of material(x, y), e.g. &GroundMaterial::noise_amplitude, without the others.
  double material_field(double GroundMaterial::*field, double x, double y) const;

  // The node square of (x, y), and the four queries above on it (the same values).
  NodeSquare locate(double x, double y) const;
  double elevation(const NodeSquare& square) const;
  Eigen::Vector2d slope(const NodeSquare& square) const;
  GroundMaterial material(const NodeSquare& square) const;
  double material_field(double GroundMaterial::*field, const NodeSquare& square) const;

 private:
  Eigen::Vector2d node_coordinates(double x, double y) const;
  Grid<double> elevation_;
  Grid<GroundMaterial> materials_;
  // Per node square, by its lower-left node: kValidSquare when its four nodes have elevations,
  // kUniformMaterial when they share one material (then no blending is needed).
  static constexpr unsigned char kValidSquare = 1, kUniformMaterial = 2;
  Grid<unsigned char> square_flags_;
  double inverse_dx_, inverse_dy_;     // 1 / geotransform[1], 1 / geotransform[5]
};

}  // namespace talus
