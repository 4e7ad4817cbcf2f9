#include "raster_fixtures.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <sstream>
#include <stdexcept>

namespace talus::test {

std::vector<float> read_band(const std::filesystem::path& path) {
  GDALAllRegister();
  GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!dataset) throw std::runtime_error("cannot open " + path.string());
  const int w = dataset->GetRasterXSize(), h = dataset->GetRasterYSize();
  std::vector<float> values(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  if (dataset->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, w, h, values.data(), w, h, GDT_Float32, 0, 0) != CE_None) {
    throw std::runtime_error("cannot read " + path.string());
  }
  return values;
}

void write_raster(const std::filesystem::path& path, const RasterFixture& fixture) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDatasetUniquePtr dataset(driver->Create(path.c_str(), fixture.width, fixture.height, 1,
                                              fixture.integer ? GDT_Int16 : GDT_Float32, nullptr));
  if (!dataset) throw std::runtime_error("cannot create " + path.string());
  double gt[6] = {fixture.x0, fixture.cell, 0, fixture.y0, 0, -fixture.cell};
  dataset->SetGeoTransform(gt);
  if (!fixture.crs.empty()) {
    OGRSpatialReference srs;
    srs.SetFromUserInput(fixture.crs.c_str());
    dataset->SetSpatialRef(&srs);
  }
  GDALRasterBand* band = dataset->GetRasterBand(1);
  band->SetNoDataValue(fixture.nodata);
  if (!fixture.unit.empty()) band->SetUnitType(fixture.unit.c_str());
  std::vector<double> values(static_cast<std::size_t>(fixture.width * fixture.height));
  for (int r = 0; r < fixture.height; ++r) {
    for (int c = 0; c < fixture.width; ++c) values[static_cast<std::size_t>(r * fixture.width + c)] = fixture.value(c, r);
  }
  if (band->RasterIO(GF_Write, 0, 0, fixture.width, fixture.height, values.data(), fixture.width, fixture.height,
                     GDT_Float64, 0, 0) != CE_None) {
    throw std::runtime_error("cannot write " + path.string());
  }
}

// A depth layer is an attribute layer with one real field, its values written exactly.
void write_vector(const std::filesystem::path& path, const std::string& crs, const std::vector<VectorFeature>& features,
                  bool with_depth_field) {
  std::vector<LayerField> fields;
  if (with_depth_field) fields.push_back({"depth", false});
  std::vector<LayerFeature> layer_features;
  for (const auto& f : features) {
    std::ostringstream depth;
    depth.precision(17);
    depth << f.depth;
    layer_features.push_back({f.wkt, {}});
    if (with_depth_field) layer_features.back().values.push_back(depth.str());
  }
  write_layer(path, crs, fields, layer_features);
}

void write_layer(const std::filesystem::path& path, const std::string& crs, const std::vector<LayerField>& fields,
                 const std::vector<LayerFeature>& features) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
  GDALDatasetUniquePtr dataset(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!dataset) throw std::runtime_error("cannot create " + path.string());
  OGRSpatialReference srs;
  srs.SetFromUserInput(crs.c_str());
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRLayer* layer = dataset->CreateLayer("release", &srs, wkbUnknown, nullptr);
  for (const auto& field : fields) {
    OGRFieldDefn definition(field.name.c_str(), field.text ? OFTString : OFTReal);
    layer->CreateField(&definition);
  }
  for (const auto& f : features) {
    OGRFeature feature(layer->GetLayerDefn());
    OGRGeometry* geometry = nullptr;
    OGRGeometryFactory::createFromWkt(f.wkt.c_str(), &srs, &geometry);
    feature.SetGeometryDirectly(geometry);
    for (std::size_t i = 0; i < fields.size() && i < f.values.size(); ++i) {
      const int index = static_cast<int>(i);
      if (!f.values[i]) {
        feature.SetFieldNull(index);
      } else if (fields[i].text) {
        feature.SetField(index, f.values[i]->c_str());
      } else {
        feature.SetField(index, std::stod(*f.values[i]));
      }
    }
    if (layer->CreateFeature(&feature) != OGRERR_NONE) throw std::runtime_error("cannot write a feature");
  }
}

}  // namespace talus::test
