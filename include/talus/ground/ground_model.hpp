// The bilinear ground model of paper 2.2: elevation and every material parameter known at the
// DEM nodes (cell centres) and interpolated bilinearly between them.
#pragma once

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

 private:
  Grid<double> elevation_;
  Grid<GroundMaterial> materials_;
};

}  // namespace talus
