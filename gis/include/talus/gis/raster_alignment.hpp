// Aligning a lithology, vegetation or release raster onto the DEM's grid (docs/architecture.md section
// 3): another CRS, resolution or extent is warped with GDALWarp; class rasters use the
// nearest cell (or the most frequent class where several source cells fall in one DEM
// cell), continuous rasters bilinear interpolation.
#pragma once

#include <filesystem>
#include <string>

#include "talus/core/grid.hpp"
#include "talus/gis/crs_option.hpp"

namespace talus::gis {

enum class ValueKind { classes, continuous };

struct AlignedRaster {
  Grid<double> values;       // on the DEM grid, input_nodata where the raster has no value
  std::string method;        // "same grid", "nearest", "mode" or "bilinear"
  bool integer_type = false; // the file stores integers (a hint that values are classes)
};

// Reads `path` onto `target` (the DEM's spec). A raster without a CRS is taken to be in the
// DEM's CRS; --crs assigns one to every input. Throws InputError naming the file when it
// cannot be read, its CRS contradicts its coordinates, or it does not overlap the DEM.
AlignedRaster align_raster(const std::filesystem::path& path, const std::string& role, const GridSpec& target,
                           ValueKind kind, const CrsOption& crs);

}  // namespace talus::gis
