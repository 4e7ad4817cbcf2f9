// Small shared pieces of the GDAL boundary: registering drivers once, opening a file as a
// raster with a one-line error naming the file, reading a dataset's grid spec, and the
// failures and CRS of the vector layers Talus writes.
#pragma once

#include <filesystem>
#include <string>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

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

// Throws std::runtime_error "cannot write PATH: STEP: GDAL's message".
[[noreturn]] void write_failure(const std::filesystem::path& path, const std::string& step);
// write_failure(path, step) unless `result` is OGRERR_NONE.
void check_written(OGRErr result, const std::filesystem::path& path, const std::string& step);

// The CRS of a vector layer written to `path`. Local coordinates (empty WKT) get the
// GeoPackage's "Undefined Cartesian SRS" (srs_id -1, metres): GDAL 3.6 stores a layer without CRS
// as srs_id 0, the undefined *geographic* one.
OGRSpatialReference vector_layer_crs(const std::string& crs_wkt, const std::filesystem::path& path);

}  // namespace talus::gis
