// Reading release rasters and release vector layers (docs/architecture.md section 3, --release), with
// the rock-fall attributes of their features (issue 16).
#include "talus/gis/release_reader.hpp"

#include <gdal_alg.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "talus/core/errors.hpp"
#include "talus/gis/dem_reader.hpp"
#include "talus/gis/gdal_dataset.hpp"
#include "talus/gis/raster_alignment.hpp"
#include "talus/gis/release_attributes.hpp"
#include "talus/gis/release_raster_conditions.hpp"

namespace talus::gis {
namespace {

struct ReleasePolygon {
  std::unique_ptr<OGRGeometry> geometry;  // in the DEM's CRS
  double depth;                           // m, > 0
  ReleaseConditions conditions;           // rock fall: what the polygon's attributes give
  std::int64_t feature_id;                // FID of its feature
};

// Keeps release cells on valid DEM cells; returns how many fell outside.
std::size_t drop_cells_outside(Grid<float>& depth, const Grid<double>& dem) {
  std::size_t outside = 0;
  for (std::size_t i = 0; i < depth.size(); ++i) {
    if (depth[i] > 0.0f && !dem.is_valid(i)) {
      depth[i] = 0.0f;
      ++outside;
    }
  }
  return outside;
}

ReleaseSet release_from_raster(const std::filesystem::path& path, const Grid<double>& dem, const CrsOption& crs,
                               const ReleaseDepthSource& depth) {
  const std::string name = describe_input(path, "release");
  const AlignedRaster aligned = align_raster(path, "release", dem.spec(), ValueKind::classes, crs);
  ReleaseSet release;
  GridSpec spec = dem.spec();
  spec.nodata = 0.0;
  release.depth = Grid<float>(spec, 0.0f);
  bool every_value_negative = true;
  for (std::size_t i = 0; i < aligned.values.size(); ++i) {
    if (!aligned.values.is_valid(i) || aligned.values[i] == 0.0) continue;
    release.depth[i] = static_cast<float>(depth.uniform ? *depth.uniform : std::abs(aligned.values[i]));
    every_value_negative = every_value_negative && aligned.values[i] < 0.0;
  }
  release.depths_from_surface_lowering = !depth.uniform && every_value_negative;
  if (release.cell_count() == 0) throw InputError(name + ": has no release cell (every value is 0 or nodata): empty release");
  drop_cells_outside(release.depth, dem);
  if (release.cell_count() == 0) throw InputError(name + ": every release cell lies outside the DEM's valid area");
  return release;
}

std::unique_ptr<OGRCoordinateTransformation> transform_to_dem(OGRLayer& layer, const GridSpec& dem, const CrsOption& crs) {
  const OGRSpatialReference* layer_srs = layer.GetSpatialRef();
  if (crs.kind == CrsOption::Kind::local || dem.crs_wkt.empty() || layer_srs == nullptr || layer_srs->IsEmpty()) return nullptr;
  OGRSpatialReference source = *layer_srs;
  source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference target;
  target.importFromWkt(dem.crs_wkt.c_str());
  target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (source.IsSame(&target)) return nullptr;
  return std::unique_ptr<OGRCoordinateTransformation>(OGRCreateCoordinateTransformation(&source, &target));
}

// Splits a geometry into release points and polygons, each with the feature's depth and
// conditions; lines are refused.
void collect(const OGRGeometry& geometry, double depth, const ReleaseConditions& conditions, std::int64_t feature_id,
             std::vector<ReleasePoint>& points, std::vector<ReleasePolygon>& polygons, const std::string& name) {
  switch (wkbFlatten(geometry.getGeometryType())) {
    case wkbPoint: {
      const auto& p = *geometry.toPoint();
      points.push_back({p.getX(), p.getY(), depth, conditions, feature_id});
      break;
    }
    case wkbPolygon:
    case wkbCurvePolygon:
      polygons.push_back({std::unique_ptr<OGRGeometry>(geometry.clone()), depth > 0 ? depth : 1.0, conditions, feature_id});
      break;
    case wkbMultiPoint:
    case wkbMultiPolygon:
    case wkbGeometryCollection:
    case wkbMultiSurface:
      for (const OGRGeometry* part : *geometry.toGeometryCollection()) {
        collect(*part, depth, conditions, feature_id, points, polygons, name);
      }
      break;
    default:
      throw InputError(name + ": has " + std::string(OGRGeometryTypeToName(geometry.getGeometryType())) +
                       " geometries; use points or polygons");
  }
}

// Burns each polygon's 1-based index onto the DEM grid (0: no polygon; the last one wins where
// they overlap); a polygon smaller than a cell still marks the cell under its centroid.
Grid<int> rasterize(const std::vector<ReleasePolygon>& polygons, const GridSpec& spec, const std::string& name) {
  Grid<int> polygon_of_cell(spec, 0);
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDatasetUniquePtr raster(mem->Create("", spec.width, spec.height, 1, GDT_Int32, nullptr));
  double gt[6];
  std::copy(spec.geotransform.begin(), spec.geotransform.end(), gt);
  raster->SetGeoTransform(gt);
  std::vector<OGRGeometryH> geometries;
  std::vector<double> burn;
  for (const auto& polygon : polygons) {
    geometries.push_back(OGRGeometry::ToHandle(polygon.geometry.get()));
    burn.push_back(static_cast<double>(burn.size() + 1));
  }
  int band = 1;
  CPLErrorReset();
  if (GDALRasterizeGeometries(GDALDataset::ToHandle(raster.get()), 1, &band, static_cast<int>(geometries.size()),
                              geometries.data(), nullptr, nullptr, burn.data(), nullptr, nullptr, nullptr) != CE_None) {
    throw InputError(name + ": rasterizing its polygons failed: " + last_gdal_error("GDAL error"));
  }
  if (raster->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, spec.width, spec.height, polygon_of_cell.values().data(),
                                         spec.width, spec.height, GDT_Int32, 0, 0) != CE_None) {
    throw InputError(name + ": reading its rasterized polygons failed");
  }
  for (std::size_t k = 0; k < polygons.size(); ++k) {
    OGRPoint centroid;
    if (polygons[k].geometry->Centroid(&centroid) != OGRERR_NONE) continue;
    int col = 0, row = 0;
    if (spec.cell_at(centroid.getX(), centroid.getY(), col, row) && polygon_of_cell.at(col, row) == 0) {
      polygon_of_cell.at(col, row) = static_cast<int>(k + 1);
    }
  }
  return polygon_of_cell;
}

// How a message names a feature: its 1-based place in its layer, its FID when the format has
// one, and its layer (empty: the file's only one).
std::string feature_name(const std::string& name, const OGRFeature& feature, std::size_t place,
                         const std::string& layer) {
  std::string text = name + ": feature " + std::to_string(place);
  if (feature.GetFID() != OGRNullFID) text += " (FID " + std::to_string(feature.GetFID()) + ")";
  if (!layer.empty()) text += " of layer '" + layer + "'";
  return text;
}

// The release cells of the polygons, with their depth and, when a polygon carries any, the
// conditions of the polygon covering each cell.
void burn_polygons(const std::vector<ReleasePolygon>& polygons, const Grid<double>& dem, ReleaseSet& release,
                   const std::string& name) {
  Grid<int> polygon_of_cell = rasterize(polygons, release.depth.spec(), name);
  release.feature_of_cell = Grid<std::int64_t>(release.depth.spec(), kNoReleaseFeature);
  for (std::size_t i = 0; i < polygon_of_cell.size(); ++i) {
    if (polygon_of_cell[i] <= 0) continue;
    const ReleasePolygon& polygon = polygons[static_cast<std::size_t>(polygon_of_cell[i] - 1)];
    release.depth[i] = static_cast<float>(polygon.depth);
    release.feature_of_cell[i] = polygon.feature_id;
  }
  drop_cells_outside(release.depth, dem);
  if (release.cell_count() == 0) throw InputError(name + ": its polygons lie outside the DEM's valid area");
  const bool any_conditions =
      std::any_of(polygons.begin(), polygons.end(), [](const ReleasePolygon& p) { return !p.conditions.empty(); });
  if (!any_conditions) return;
  for (const auto& polygon : polygons) release.condition_sets.push_back(polygon.conditions);
  release.condition_set_of_cell = std::move(polygon_of_cell);
}

ReleaseSet release_from_vector(GDALDataset& dataset, const std::filesystem::path& path, const Grid<double>& dem,
                               const CrsOption& crs, const std::optional<Rock>& run_rock,
                               const ReleaseDepthSource& depth_source) {
  const std::string name = describe_input(path, "release");
  std::vector<ReleasePoint> points;
  std::vector<ReleasePolygon> polygons;
  std::size_t features = 0;
  const bool several_layers = dataset.GetLayerCount() > 1;
  for (OGRLayer* layer : dataset.GetLayers()) {
    const auto transform = transform_to_dem(*layer, dem.spec(), crs);
    const int depth_field = layer->GetLayerDefn()->GetFieldIndex(depth_source.field.c_str());
    const std::string layer_name = several_layers ? std::string(layer->GetName()) : std::string();
    std::size_t place = 0;
    for (auto& feature : *layer) {
      ++place;
      const OGRGeometry* original = feature->GetGeometryRef();
      if (original == nullptr || original->IsEmpty()) continue;
      ++features;
      std::unique_ptr<OGRGeometry> geometry(original->clone());
      if (transform && geometry->transform(transform.get()) != OGRERR_NONE) {
        throw InputError(name + ": a geometry cannot be transformed to the DEM's CRS");
      }
      const double depth = depth_source.uniform    ? *depth_source.uniform
                           : depth_field >= 0     ? std::abs(feature->GetFieldAsDouble(depth_field))
                                                  : 0.0;
      const ReleaseConditions conditions =
          run_rock ? read_release_conditions(*feature, *run_rock, feature_name(name, *feature, place, layer_name))
                   : ReleaseConditions{};
      collect(*geometry, depth, conditions, feature->GetFID(), points, polygons, name);
    }
  }
  if (features == 0) throw InputError(name + ": has no features: empty release");

  ReleaseSet release;
  GridSpec spec = dem.spec();
  spec.nodata = 0.0;
  release.depth = Grid<float>(spec, 0.0f);
  if (!polygons.empty()) burn_polygons(polygons, dem, release, name);
  std::size_t index = 0;
  for (const auto& p : points) {
    ++index;
    int col = 0, row = 0;
    if (!spec.cell_at(p.x, p.y, col, row) || !dem.is_valid(col, row)) {
      std::ostringstream message;
      message.precision(10);
      message << name << ": point " << index << " of " << points.size() << " (x " << p.x << ", y " << p.y
              << ") lies outside the DEM's valid area";
      throw InputError(message.str());
    }
  }
  release.points = std::move(points);
  return release;
}

}  // namespace

ReleaseSet read_release(const std::filesystem::path& path, const Grid<double>& dem, const CrsOption& crs,
                        const std::optional<Rock>& run_rock, const ReleaseDepthSource& depth) {
  ensure_gdal_ready();
  const std::string name = describe_input(path, "release");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(name + ": file not found");
  CPLErrorReset();
  GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!dataset) throw InputError(name + ": not a raster or vector layer GDAL can read");
  if (dataset->GetLayerCount() > 0) return release_from_vector(*dataset, path, dem, crs, run_rock, depth);
  if (dataset->GetRasterCount() > 0) {
    dataset.reset();
    ReleaseSet release = release_from_raster(path, dem, crs, depth);
    if (run_rock) add_raster_conditions(path, dem.spec(), crs, *run_rock, release);
    return release;
  }
  throw InputError(name + ": has neither a raster band nor a vector layer");
}

}  // namespace talus::gis
