// Alignment of secondary rasters onto the DEM grid with GDALWarp (docs/architecture.md section 3).
#include "talus/gis/raster_alignment.hpp"

#include <gdal_utils.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "talus/core/errors.hpp"
#include "talus/gis/dem_reader.hpp"
#include "talus/gis/gdal_dataset.hpp"

namespace talus::gis {
namespace {

struct Bounds {
  double x0, y0, x1, y1;
  bool overlaps(const Bounds& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

Bounds bounds_of(const GridSpec& spec) {
  const auto gt = spec.own_geotransform();
  return {gt[0], gt[3] + spec.height * gt[5], gt[0] + spec.width * gt[1], gt[3]};
}

// The source's bounds expressed in the target CRS (both may be empty: local coordinates).
Bounds bounds_in_target(const GridSpec& source, const OGRSpatialReference& source_srs,
                        const OGRSpatialReference& target_srs, const std::string& name) {
  const Bounds b = bounds_of(source);
  if (source_srs.IsEmpty() || target_srs.IsEmpty() || source_srs.IsSame(&target_srs)) return b;
  std::unique_ptr<OGRCoordinateTransformation> transform(OGRCreateCoordinateTransformation(&source_srs, &target_srs));
  Bounds out{};
  if (!transform || !transform->TransformBounds(b.x0, b.y0, b.x1, b.y1, &out.x0, &out.y0, &out.x1, &out.y1, 21)) {
    throw InputError(name + ": its extent cannot be transformed to the DEM's CRS");
  }
  return out;
}

GDALDatasetUniquePtr empty_target(const GridSpec& target, const OGRSpatialReference& target_srs) {
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDatasetUniquePtr dataset(mem->Create("", target.width, target.height, 1, GDT_Float64, nullptr));
  std::array<double, 6> gt = target.own_geotransform();
  dataset->SetGeoTransform(gt.data());
  if (!target_srs.IsEmpty()) dataset->SetSpatialRef(&target_srs);
  GDALRasterBand* band = dataset->GetRasterBand(1);
  band->SetNoDataValue(input_nodata);
  band->Fill(input_nodata);
  return dataset;
}

void warp_into(GDALDataset& source, GDALDataset& destination, const std::string& method,
               const std::string& source_wkt, const std::string& name) {
  std::vector<std::string> arguments = {"-r", method, "-dstnodata", "-9999", "-wo", "INIT_DEST=NO_DATA"};
  if (!source_wkt.empty()) {
    arguments.insert(arguments.end(), {"-s_srs", source_wkt});
  }
  std::vector<char*> argv;
  for (auto& a : arguments) argv.push_back(a.data());
  argv.push_back(nullptr);
  GDALWarpAppOptions* options = GDALWarpAppOptionsNew(argv.data(), nullptr);
  GDALDatasetH source_handle = GDALDataset::ToHandle(&source);
  int usage_error = 0;
  CPLErrorReset();
  GDALDatasetH result = GDALWarp(nullptr, GDALDataset::ToHandle(&destination), 1, &source_handle, options, &usage_error);
  GDALWarpAppOptionsFree(options);
  if (result == nullptr) throw InputError(name + ": alignment onto the DEM grid failed: " + last_gdal_error("GDAL warp error"));
}

// The band's values over cells [col, col + w) x [row, row + h) (the whole band by default),
// nodata and non-finite values as input_nodata.
std::vector<double> read_band(GDALDataset& dataset, const std::string& name, int col = 0, int row = 0, int w = 0,
                              int h = 0) {
  GDALRasterBand* band = dataset.GetRasterBand(1);
  if (w == 0) w = dataset.GetRasterXSize();
  if (h == 0) h = dataset.GetRasterYSize();
  std::vector<double> values(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  CPLErrorReset();
  if (band->RasterIO(GF_Read, col, row, w, h, values.data(), w, h, GDT_Float64, 0, 0) != CE_None) {
    throw InputError(name + ": cannot read its values: " + last_gdal_error("read error"));
  }
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  for (double& v : values) {
    if (!std::isfinite(v) || (has_nodata && v == nodata)) v = input_nodata;
  }
  return values;
}

}  // namespace

AlignedRaster align_raster(const std::filesystem::path& path, const std::string& role, const GridSpec& target,
                           ValueKind kind, const CrsOption& crs) {
  const std::string name = describe_input(path, role);
  GDALDatasetUniquePtr dataset = open_raster(path, role);
  GridSpec source = raster_grid(*dataset, name);

  OGRSpatialReference target_srs;
  target_srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (!target.crs_wkt.empty()) target_srs.importFromWkt(target.crs_wkt.c_str());

  // The source's CRS: its own when it has one that fits its coordinates; otherwise the DEM's
  // (which --crs may have assigned). A geographic CRS on metre coordinates is an error unless
  // --crs says which CRS the inputs are really in.
  OGRSpatialReference source_srs;
  source_srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const OGRSpatialReference* file_srs = dataset->GetSpatialRef();
  if (crs.kind != CrsOption::Kind::local) refuse_geocentric_crs(file_srs, name);
  const Bounds own = bounds_of(source);
  const bool own_is_contradicted = file_srs != nullptr && file_srs->IsGeographic() &&
                                   (own.x0 < -180.0 || own.x1 > 360.0 || own.y0 < -90.0 || own.y1 > 90.0);
  if (own_is_contradicted && crs.kind == CrsOption::Kind::from_file) {
    throw InputError(name + ": its CRS is geographic (degrees) but its coordinates are metres; give the right CRS with --crs");
  }
  std::string assigned_wkt;
  if (file_srs != nullptr && !file_srs->IsEmpty() && !own_is_contradicted && crs.kind != CrsOption::Kind::local) {
    source_srs = *file_srs;
    source_srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  } else {
    source_srs = target_srs;
    assigned_wkt = target.crs_wkt;
  }

  const Bounds dem = bounds_of(target);
  const Bounds here = bounds_in_target(source, source_srs, target_srs, name);
  if (!here.overlaps(dem)) throw InputError(name + ": does not overlap the DEM");

  AlignedRaster result;
  const GDALDataType type = dataset->GetRasterBand(1)->GetRasterDataType();
  result.integer_type = GDALDataTypeIsInteger(type) != 0;
  source.crs_wkt = target.crs_wkt;
  const bool same_crs = source_srs.IsEmpty() == target_srs.IsEmpty() &&
                        (source_srs.IsEmpty() || source_srs.IsSame(&target_srs));
  GridSpec aligned = target;
  aligned.nodata = input_nodata;
  if (same_crs && source.same_grid(target)) {
    result.method = "same grid";
    result.values = Grid<double>(aligned, read_band(*dataset, name));
    return result;
  }
  if (same_crs && target.is_window() && source.same_grid(target.whole())) {
    // A tile's window of a raster on the DEM's grid: its own cells, read as they are.
    result.method = "same grid";
    result.values = Grid<double>(aligned, read_band(*dataset, name, target.col_offset, target.row_offset,
                                                    target.width, target.height));
    return result;
  }
  if (kind == ValueKind::continuous) {
    result.method = "bilinear";
  } else {
    // Several source cells per DEM cell: the most frequent class; otherwise the nearest.
    const double source_cell = (here.x1 - here.x0) / source.width;
    result.method = source_cell < 0.5 * target.cell_width() ? "mode" : "nearest";
  }
  GDALDatasetUniquePtr destination = empty_target(target, target_srs);
  warp_into(*dataset, *destination, result.method == "nearest" ? "near" : result.method, assigned_wkt, name);
  result.values = Grid<double>(aligned, read_band(*destination, name));
  return result;
}

}  // namespace talus::gis
