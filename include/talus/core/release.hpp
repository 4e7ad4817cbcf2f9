// Where material is released (DESIGN.md section 3, --release): cells from a raster or
// polygons, and points. Rock fall starts one source per cell or point; mud flow releases the
// cells' depth.
#pragma once

#include <cstddef>
#include <vector>

#include "talus/core/grid.hpp"

namespace talus {

struct ReleasePoint {
  double x = 0, y = 0;   // m, in the DEM's CRS
  double depth = 0;      // m, from a `depth` attribute (0 when none)
};

struct ReleaseSet {
  Grid<float> depth;                 // m on the DEM grid: > 0 in release cells, 0 elsewhere
  std::vector<ReleasePoint> points;  // point sources

  std::size_t cell_count() const;    // cells with depth > 0
  double area() const;               // m2 covered by release cells
  double volume() const;             // m3: sum of depth x cell area
  std::size_t source_count() const { return cell_count() + points.size(); }
};

}  // namespace talus
