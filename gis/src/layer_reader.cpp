#include "talus/gis/layer_reader.hpp"

#include "talus/core/errors.hpp"
#include "talus/gis/gdal_dataset.hpp"

namespace talus::gis {

Grid<float> read_layer(const std::filesystem::path& path) {
  GDALDatasetUniquePtr dataset = open_raster(path, "layer");
  GridSpec spec = raster_grid(*dataset, describe_input(path, "layer"));
  spec.crs_wkt = wkt_of(dataset->GetSpatialRef());
  GDALRasterBand* band = dataset->GetRasterBand(1);
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  if (has_nodata) spec.nodata = nodata;
  Grid<float> grid(spec);
  if (band->RasterIO(GF_Read, 0, 0, spec.width, spec.height, grid.values().data(), spec.width, spec.height,
                     GDT_Float32, 0, 0) != CE_None) {
    throw InputError(describe_input(path, "layer") + ": " + last_gdal_error("cannot read band 1"));
  }
  return grid;
}

}  // namespace talus::gis
