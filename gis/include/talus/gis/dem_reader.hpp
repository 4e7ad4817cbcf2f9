// Reading the DEM (docs/architecture.md section 3): the grid every other input is aligned onto.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "talus/core/grid.hpp"
#include "talus/gis/crs_option.hpp"

namespace talus::gis {

// Internal nodata value of every grid Talus builds from its inputs.
inline constexpr double input_nodata = -9999.0;

struct DemInput {
  Grid<double> elevation;            // m above the vertical datum, input_nodata outside the valid area
  std::string crs_name;              // e.g. "MGI / Austria Lambert (EPSG:31287)" or "local"
  std::vector<std::string> notes;    // what was done to the file on the way in
};

// Reads a DEM and applies the CRS rules of docs/architecture.md section 3:
// - --crs assigns a CRS (or "local"); without it a DEM with no CRS is refused;
// - a geographic CRS whose coordinates are plainly metres is refused;
// - a geographic DEM (degrees) is reprojected to its UTM zone, and a note says so;
// - a horizontal unit other than metres, or a vertical unit other than metres, is refused;
// - nodata cells (and NaN) become input_nodata, PixelIsPoint rasters are shifted half a cell
//   (GDAL's reading), and a border of exact zeros around valid terrain (a common export
//   artefact) becomes nodata.
// Throws InputError with one line naming the file and the problem.
DemInput read_dem(const std::filesystem::path& path, const CrsOption& crs);

// Human-readable name of a CRS given as WKT ("local" when empty).
std::string crs_display_name(const std::string& wkt);

}  // namespace talus::gis
