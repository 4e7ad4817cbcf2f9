// Opening files through GDAL with clear one-line errors (docs/architecture.md section 3, exit code 2).
#include "talus/gis/gdal_dataset.hpp"

#include <cpl_error.h>
#include <ogr_spatialref.h>

#include <mutex>
#include <string>
#include <stdexcept>

#include "talus/core/errors.hpp"

namespace talus::gis {

void ensure_gdal_ready() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);
  });
}

std::string last_gdal_error(const std::string& fallback) {
  const char* message = CPLGetLastErrorMsg();
  return (message != nullptr && *message != '\0') ? std::string(message) : fallback;
}

std::string describe_input(const std::filesystem::path& path, const std::string& role) {
  return path.string() + " (" + role + ")";
}

GDALDatasetUniquePtr open_raster(const std::filesystem::path& path, const std::string& role) {
  ensure_gdal_ready();
  const std::string name = describe_input(path, role);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(name + ": file not found");
  if (std::filesystem::is_directory(path, ec)) throw InputError(name + ": is a folder, not a raster file");
  CPLErrorReset();
  GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!dataset) throw InputError(name + ": not a raster GDAL can read");
  if (dataset->GetRasterCount() < 1) throw InputError(name + ": has no raster band");
  return dataset;
}

GridSpec raster_grid(GDALDataset& dataset, const std::string& name) {
  GridSpec spec;
  spec.width = dataset.GetRasterXSize();
  spec.height = dataset.GetRasterYSize();
  double gt[6];
  if (dataset.GetGeoTransform(gt) != CE_None) throw InputError(name + ": has no georeferencing (geotransform)");
  if (gt[2] != 0.0 || gt[4] != 0.0) throw InputError(name + ": rotated grids are not supported; warp it north-up first");
  if (gt[1] <= 0.0 || gt[5] >= 0.0) throw InputError(name + ": grid is not north-up (cell size " +
                                                     std::to_string(gt[1]) + " x " + std::to_string(gt[5]) + ")");
  for (int k = 0; k < 6; ++k) spec.geotransform[static_cast<std::size_t>(k)] = gt[k];
  return spec;
}

std::string wkt_of(const OGRSpatialReference* srs) {
  if (srs == nullptr || srs->IsEmpty()) return {};
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT2_2019", nullptr};
  srs->exportToWkt(&wkt, options);
  std::string text = wkt != nullptr ? wkt : "";
  CPLFree(wkt);
  return text;
}

void refuse_geocentric_crs(const OGRSpatialReference* srs, const std::string& name) {
  if (srs == nullptr || !srs->IsGeocentric()) return;
  const char* crs_name = srs->GetName();
  throw InputError(name + ": its CRS" + (crs_name ? " (" + std::string(crs_name) + ")" : std::string()) +
                   " is geocentric (X, Y, Z from the Earth's centre), not a map's; reproject it to a projected CRS "
                   "(gdalwarp -t_srs EPSG:nnnn) or give the right one with --crs");
}

void write_failure(const std::filesystem::path& path, const std::string& step) {
  throw std::runtime_error("cannot write " + path.string() + ": " + step + ": " + last_gdal_error("failed"));
}

void check_written(OGRErr result, const std::filesystem::path& path, const std::string& step) {
  if (result != OGRERR_NONE) write_failure(path, step);
}

OGRLayer& create_vector_layer(GDALDataset& dataset, const std::filesystem::path& path, const std::string& crs_wkt,
                              const VectorLayerSpec& spec) {
  OGRSpatialReference srs;
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (crs_wkt.empty()) {
    srs.SetLocalCS("Undefined Cartesian SRS");
    srs.SetLinearUnits(SRS_UL_METER, 1.0);
  } else {
    check_written(srs.importFromWkt(crs_wkt.c_str()), path, "reading the CRS");
  }
  const std::string identifier = std::string("IDENTIFIER=") + spec.identifier;
  const std::string description = std::string("DESCRIPTION=") + spec.description;
  const char* const options[] = {identifier.c_str(), description.c_str(),
                                 spec.spatial_index ? "SPATIAL_INDEX=YES" : "SPATIAL_INDEX=NO", nullptr};
  OGRLayer* layer = dataset.CreateLayer(spec.name, &srs, spec.geometry, const_cast<char**>(options));
  if (layer == nullptr) write_failure(path, "creating the layer");
  for (const VectorField& field : spec.fields) {
    OGRFieldDefn definition(field.name, field.type);
    definition.SetAlternativeName(field.alias);
    check_written(layer->CreateField(&definition), path, std::string("creating the field ") + field.name);
  }
  if (layer->SetMetadataItem("TALUS_VERSION", TALUS_VERSION) != CE_None) write_failure(path, "setting the metadata");
  return *layer;
}

}  // namespace talus::gis
