// Small shared pieces of the GDAL boundary: registering drivers once, opening a file as a
// raster with a one-line error naming the file, reading a dataset's grid spec, and the
// failures and the creation of the vector layers Talus writes.
#pragma once

#include <filesystem>
#include <span>
#include <string>

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

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

// A map's raster has a projected, geographic or local CRS; a geocentric one (X, Y, Z from the
// Earth's centre, such as EPSG:4914) is InputError naming the file, before PROJ searches for a
// transformation from it (seconds, a fuzz finding).
void refuse_geocentric_crs(const OGRSpatialReference* srs, const std::string& name);

// Throws std::runtime_error "cannot write PATH: STEP: GDAL's message".
[[noreturn]] void write_failure(const std::filesystem::path& path, const std::string& step);
// write_failure(path, step) unless `result` is OGRERR_NONE.
void check_written(OGRErr result, const std::filesystem::path& path, const std::string& step);

// One attribute of a vector layer Talus writes: its name, type and the alias QGIS shows.
struct VectorField {
  const char* name;
  OGRFieldType type;
  const char* alias;
};

// What create_vector_layer makes: the layer's name and geometry type, the GeoPackage
// identifier and description QGIS shows, and the attributes in order.
struct VectorLayerSpec {
  const char* name;
  OGRwkbGeometryType geometry;
  const char* identifier;
  const char* description;
  std::span<const VectorField> fields;
  bool spatial_index = true;  // false: no R-tree (a layer read by attribute, not drawn at scale)
};

// Creates the layer in `dataset` (being written to `path`) with its fields and a TALUS_VERSION
// metadata item; write_failure on any error. The CRS is `crs_wkt`; local coordinates (empty
// WKT) get the GeoPackage's "Undefined Cartesian SRS" (srs_id -1, metres): GDAL 3.6 stores a
// layer without CRS as srs_id 0, the undefined *geographic* one.
OGRLayer& create_vector_layer(GDALDataset& dataset, const std::filesystem::path& path, const std::string& crs_wkt,
                              const VectorLayerSpec& spec);

}  // namespace talus::gis
