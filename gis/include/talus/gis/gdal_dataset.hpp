// Small shared pieces of the GDAL boundary: registering drivers once, opening a file as a
// raster with a one-line error naming the file, and reading a dataset's grid spec.
#pragma once

#include <filesystem>
#include <string>

#include <gdal_priv.h>

#include "talus/core/grid_spec.hpp"

namespace talus::gis {

// Registers GDAL's drivers once and routes GDAL's own messages away from the terminal (the
// boundary turns failures into InputError messages instead).
void ensure_gdal_ready();

// The last GDAL error message, or a fallback when GDAL gave none.
std::string last_gdal_error(const std::string& fallback);

// "<path> (<role>)": how every message names an input file.
std::string describe_input(const std::filesystem::path& path, const std::string& role);

// Opens a raster for reading; throws InputError when the file is missing or not a raster.
GDALDatasetUniquePtr open_raster(const std::filesystem::path& path, const std::string& role);

// Size and north-up geotransform of a dataset; throws InputError for rotated grids. The CRS
// is left empty: callers decide which CRS applies.
GridSpec raster_grid(GDALDataset& dataset, const std::string& name);

// WKT2 text of a spatial reference, empty for none.
std::string wkt_of(const OGRSpatialReference* srs);

}  // namespace talus::gis
