// Entrainment of erodible material lying on the terrain (paper 4.1, last paragraph; issue 5):
// a flowing particle erodes the bed under it at the rate E h |u| (m/s; McDougall & Hungr 2005),
// E the entrainment rate (1/m), h its flow depth, u its speed, until the cell's erodible depth is
// used up. The eroded mass joins the particle at rest, so its momentum is unchanged.
// Erodible and eroded depths are vertical depths per DEM cell (m), as in the erodible raster: a
// cell holds depth x cell area (m3) of material. A particle's horizontal footprint is a square of
// area m / sigma (m2, sigma its areal density; the cell area when sigma is 0) centred on it; it
// erodes the depth E h |u| dt from every cell the square overlaps, over the overlap, so a
// particle wider than a cell erodes all the cells under it.
#pragma once

#include <vector>

#include "talus/core/grid.hpp"
#include "talus/ground/ground_model.hpp"
#include "talus/mudflow/particle_set.hpp"

namespace talus {

class Entrainment {
 public:
  // erodible: depth (m) per DEM cell (negative, NaN and nodata count as none, and so do cells
  // outside the DEM's valid area), on the DEM grid (GridMismatch otherwise). rate E (1/m),
  // mud_density rho0 (kg/m3).
  Entrainment(const GroundModel& ground, const Grid<float>& erodible, double rate, double mud_density);

  // Erodes for `step` (s) under the flowing particles flagged in `active` (all when empty), in
  // index order, each over the cells under its footprint; adds the mass to them and the eroded
  // depth to `eroded` (m per cell, DEM grid). Returns the volume entrained (m3).
  double erode(ParticleSet& particles, const std::vector<char>& active, double step, Grid<float>& eroded);

  double remaining_volume() const;  // m3 still erodible

 private:
  const GroundModel& ground_;
  Grid<double> remaining_;  // m per cell
  double rate_;             // 1/m
  double mud_density_;      // kg/m3
};

}  // namespace talus
