// hazard.tif's style and hazard_zones.gpkg (hazard_zones_writer.hpp).
#include "talus/gis/hazard_zones_writer.hpp"

#include <gdal_alg.h>

#include <array>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "talus/gis/gdal_dataset.hpp"
#include "talus/gis/intensity_style.hpp"
#include "talus/gis/xml_text.hpp"

namespace talus::gis {
namespace {

constexpr std::array<VectorField, 3> kFields = {{{"degree", OFTInteger, "hazard degree (value)"},
                                                 {"name", OFTString, "hazard degree"},
                                                 {"label", OFTString, "meaning"}}};
constexpr VectorLayerSpec kLayer = {"hazard_zones", wkbPolygon, "hazard_zones",
                                    "Hazard zones of a Talus study: degree from intensity and return period", kFields};

// "#e60000" as QGIS's "230,0,0,255".
std::string rgba(const std::string& colour) {
  const auto channel = [&](int k) { return std::to_string(std::stoi(colour.substr(1 + 2 * k, 2), nullptr, 16)); };
  return channel(0) + "," + channel(1) + "," + channel(2) + ",255";
}

// The categorized style of hazard_zones.gpkg: each degree's fill colour, a thin dark outline.
std::string zones_style_qml(const HazardMatrix& matrix) {
  std::ostringstream qml;
  qml << "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n"
         "<qgis version=\"3.22.16-Białowieża\" styleCategories=\"AllStyleCategories\">\n"
         "  <renderer-v2 type=\"categorizedSymbol\" attr=\"degree\" symbollevels=\"0\" enableorderby=\"0\" "
         "forceraster=\"0\">\n    <categories>\n";
  for (std::size_t k = 0; k < matrix.degrees.size(); ++k) {
    const HazardDegree& d = matrix.degrees[k];
    qml << "      <category symbol=\"" << k << "\" value=\"" << d.value << "\" label=\"" << xml_escaped(d.label)
        << "\" render=\"true\"/>\n";
  }
  qml << "    </categories>\n    <symbols>\n";
  for (std::size_t k = 0; k < matrix.degrees.size(); ++k) {
    qml << "      <symbol type=\"fill\" name=\"" << k << "\" alpha=\"0.8\" clip_to_extent=\"1\" force_rhr=\"0\">\n"
        << "        <layer class=\"SimpleFill\" pass=\"0\" enabled=\"1\" locked=\"0\">\n"
        << "          <prop k=\"color\" v=\"" << rgba(matrix.degrees[k].colour) << "\"/>\n"
        << "          <prop k=\"style\" v=\"solid\"/>\n"
        << "          <prop k=\"outline_color\" v=\"60,60,60,255\"/>\n"
        << "          <prop k=\"outline_style\" v=\"solid\"/>\n"
        << "          <prop k=\"outline_width\" v=\"0.2\"/>\n"
        << "          <prop k=\"outline_width_unit\" v=\"MM\"/>\n"
        << "        </layer>\n      </symbol>\n";
  }
  qml << "    </symbols>\n  </renderer-v2>\n  <aliases>\n";
  for (std::size_t k = 0; k < kFields.size(); ++k) {
    qml << "    <alias field=\"" << kFields[k].name << "\" index=\"" << k << "\" name=\"" << kFields[k].alias << "\"/>\n";
  }
  qml << "  </aliases>\n  <layerGeometryType>2</layerGeometryType>\n</qgis>\n";
  return qml.str();
}

void write_zones(const std::filesystem::path& path, const Grid<float>& hazard, const HazardMatrix& matrix) {
  ensure_gdal_ready();
  const GridSpec& spec = hazard.spec();
  GDALDriver* memory = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* gpkg = GetGDALDriverManager()->GetDriverByName("GPKG");
  if (memory == nullptr || gpkg == nullptr) throw std::runtime_error("cannot write " + path.string() + ": GDAL lacks MEM or GPKG");
  // The degrees as integers, and a mask of the cells with a degree.
  GDALDatasetUniquePtr cells(memory->Create("", spec.width, spec.height, 2, GDT_Int32, nullptr));
  if (!cells) write_failure(path, "making the degree raster");
  std::array<double, 6> geotransform = spec.own_geotransform();
  cells->SetGeoTransform(geotransform.data());
  std::vector<std::int32_t> degree(hazard.size()), mask(hazard.size());
  for (std::size_t cell = 0; cell < hazard.size(); ++cell) {
    degree[cell] = hazard.is_valid(cell) ? static_cast<std::int32_t>(hazard[cell]) : 0;
    mask[cell] = degree[cell] > 0 ? 1 : 0;
  }
  for (int b = 1; b <= 2; ++b) {
    if (cells->GetRasterBand(b)->RasterIO(GF_Write, 0, 0, spec.width, spec.height, b == 1 ? degree.data() : mask.data(),
                                          spec.width, spec.height, GDT_Int32, 0, 0) != CE_None) {
      write_failure(path, "filling the degree raster");
    }
  }
  std::error_code error;
  std::filesystem::remove(path, error);
  CPLErrorReset();
  GDALDatasetUniquePtr dataset(gpkg->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!dataset) write_failure(path, "creating the GeoPackage");
  CPLErrorReset();
  try {
    OGRLayer& layer = create_vector_layer(*dataset, path, spec.crs_wkt, kLayer);
    check_written(dataset->StartTransaction(), path, "starting the transaction");
    if (GDALPolygonize(cells->GetRasterBand(1), cells->GetRasterBand(2), &layer, 0, nullptr, nullptr, nullptr) != CE_None) {
      write_failure(path, "joining the cells into polygons");
    }
    std::map<int, const HazardDegree*> by_value;
    for (const HazardDegree& d : matrix.degrees) by_value[d.value] = &d;
    layer.ResetReading();
    std::vector<std::unique_ptr<OGRFeature>> features;
    for (OGRFeature* feature = layer.GetNextFeature(); feature != nullptr; feature = layer.GetNextFeature()) {
      features.emplace_back(feature);
    }
    for (const auto& feature : features) {
      const auto found = by_value.find(feature->GetFieldAsInteger("degree"));
      if (found == by_value.end()) continue;
      feature->SetField("name", found->second->name.c_str());
      feature->SetField("label", found->second->label.c_str());
      check_written(layer.SetFeature(feature.get()), path, "naming a zone");
    }
    check_written(dataset->CommitTransaction(), path, "committing the zones");
    dataset.reset();
    if (CPLGetLastErrorType() == CE_Failure) write_failure(path, "closing the GeoPackage");
  } catch (...) {
    dataset.reset();
    std::filesystem::remove(path, error);
    throw;
  }
}

}  // namespace

std::string hazard_style_qml(const HazardMatrix& matrix) {
  IntensityScheme palette;  // the paletted style of classes that intensity.tif uses
  for (const HazardDegree& d : matrix.degrees) palette.classes.push_back({d.value, d.name, d.label, d.colour, {}});
  return intensity_style_qml(palette);
}

void add_hazard_zones(LayerWriter& writer, const Grid<float>& hazard, const HazardMatrix& matrix) {
  write_zones(writer.temporary_path("hazard_zones.gpkg"), hazard, matrix);
  std::ofstream qml(writer.temporary_path("hazard_zones.qml"), std::ios::binary);
  qml << zones_style_qml(matrix);
  qml.close();
  if (!qml) throw std::runtime_error("cannot write " + (writer.folder() / "hazard_zones.qml").string());
}

}  // namespace talus::gis
