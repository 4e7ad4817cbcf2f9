// Reading --release (DESIGN.md section 3): a raster (non-zero cells are sources, the value is
// a depth in metres and negative values count as depths too) or a vector layer through OGR
// (points, or polygons rasterized onto the DEM grid, with an optional `depth` attribute),
// reprojected to the DEM's CRS.
#pragma once

#include <filesystem>

#include "talus/core/release.hpp"
#include "talus/gis/crs_option.hpp"

namespace talus::gis {

// Throws InputError naming the file when it is unreadable, empty, of an unsupported geometry,
// or lies outside the DEM's valid area.
ReleaseSet read_release(const std::filesystem::path& path, const Grid<double>& dem, const CrsOption& crs);

}  // namespace talus::gis
