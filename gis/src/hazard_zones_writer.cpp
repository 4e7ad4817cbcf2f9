// hazard.tif's style and hazard_zones.gpkg (hazard_zones_writer.hpp).
#include "talus/gis/hazard_zones_writer.hpp"

#include <gdal_alg.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
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

// The hatching of residual hazard: its degree's pale yellow is invisible as thin lines.
constexpr const char* kResidualHatch = "150,130,0,255";

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
    // Residual hazard is a hatching over the map, as hazard zone plans draw it, not a solid fill.
    const bool residual = matrix.degrees[k].name == "residual";
    qml << "      <symbol type=\"fill\" name=\"" << k << "\" alpha=\"0.8\" clip_to_extent=\"1\" force_rhr=\"0\">\n"
        << "        <layer class=\"SimpleFill\" pass=\"0\" enabled=\"1\" locked=\"0\">\n"
        << "          <prop k=\"color\" v=\"" << (residual ? std::string(kResidualHatch) : rgba(matrix.degrees[k].colour))
        << "\"/>\n"
        << "          <prop k=\"style\" v=\"" << (residual ? "b_diagonal" : "solid") << "\"/>\n"
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

// The 4-connected patches of equal degree among the cells `inside` marks (a flood fill).
long patches_of(const std::vector<std::int32_t>& degree, const std::vector<std::int32_t>& inside, int width, int height) {
  std::vector<bool> seen(degree.size(), false);
  std::vector<std::size_t> stack;
  long patches = 0;
  for (std::size_t start = 0; start < degree.size(); ++start) {
    if (inside[start] == 0 || seen[start]) continue;
    ++patches;
    seen[start] = true;
    stack.push_back(start);
    while (!stack.empty()) {
      const std::size_t cell = stack.back();
      stack.pop_back();
      const int row = static_cast<int>(cell / width), col = static_cast<int>(cell % width);
      const std::array<std::array<int, 2>, 4> steps{{{-1, 0}, {1, 0}, {0, -1}, {0, 1}}};
      for (const auto& [dr, dc] : steps) {
        const int r = row + dr, c = col + dc;
        if (r < 0 || r >= height || c < 0 || c >= width) continue;
        const std::size_t near = static_cast<std::size_t>(r) * width + c;
        if (inside[near] != 0 && !seen[near] && degree[near] == degree[cell]) {
          seen[near] = true;
          stack.push_back(near);
        }
      }
    }
  }
  return patches;
}

// A 3 x 3 majority filter over the degrees of the valid cells (0: none), once: a cell takes the
// degree most of its valid neighbours and itself have; in a tie it keeps its own when that is
// among the tied, else takes the highest of them, so that smoothing never lowers a tied cell.
std::vector<std::int32_t> majority_smoothed(const std::vector<std::int32_t>& degree, const std::vector<std::int32_t>& valid,
                                            int width, int height) {
  std::vector<std::int32_t> smoothed = degree;
  const std::int32_t highest = degree.empty() ? 0 : std::max(0, *std::max_element(degree.begin(), degree.end()));
  std::vector<int> votes(static_cast<std::size_t>(highest) + 1);  // per degree, reused cell after cell
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const std::size_t cell = static_cast<std::size_t>(row) * width + col;
      if (valid[cell] == 0) continue;
      std::fill(votes.begin(), votes.end(), 0);
      for (int r = std::max(row - 1, 0); r <= std::min(row + 1, height - 1); ++r) {
        for (int c = std::max(col - 1, 0); c <= std::min(col + 1, width - 1); ++c) {
          const std::size_t near = static_cast<std::size_t>(r) * width + c;
          if (valid[near] != 0) ++votes[static_cast<std::size_t>(degree[near])];
        }
      }
      const int most = *std::max_element(votes.begin(), votes.end());
      if (votes[static_cast<std::size_t>(degree[cell])] == most) continue;
      for (std::size_t d = 0; d < votes.size(); ++d) {
        if (votes[d] == most) smoothed[cell] = static_cast<std::int32_t>(d);  // the last tied is the highest
      }
    }
  }
  return smoothed;
}

ZoneCounts write_zones(const std::filesystem::path& path, const Grid<float>& hazard, const HazardMatrix& matrix,
                       const ZoneGeneralisation& generalisation) {
  ensure_gdal_ready();
  const GridSpec& spec = hazard.spec();
  GDALDriver* memory = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* gpkg = GetGDALDriverManager()->GetDriverByName("GPKG");
  if (memory == nullptr || gpkg == nullptr) throw std::runtime_error("cannot write " + path.string() + ": GDAL lacks MEM or GPKG");
  // Band 1: the degrees as integers; band 2: the valid cells; band 3: the cells with a degree.
  GDALDatasetUniquePtr cells(memory->Create("", spec.width, spec.height, 3, GDT_Int32, nullptr));
  if (!cells) write_failure(path, "making the degree raster");
  std::array<double, 6> geotransform = spec.own_geotransform();
  cells->SetGeoTransform(geotransform.data());
  std::vector<std::int32_t> degree(hazard.size()), valid(hazard.size());
  for (std::size_t cell = 0; cell < hazard.size(); ++cell) {
    valid[cell] = hazard.is_valid(cell) ? 1 : 0;
    degree[cell] = valid[cell] != 0 ? static_cast<std::int32_t>(hazard[cell]) : 0;
  }
  const auto write_band = [&](int band, const std::vector<std::int32_t>& values) {
    if (cells->GetRasterBand(band)->RasterIO(GF_Write, 0, 0, spec.width, spec.height, const_cast<std::int32_t*>(values.data()),
                                             spec.width, spec.height, GDT_Int32, 0, 0) != CE_None) {
      write_failure(path, "filling the degree raster");
    }
  };
  const auto read_band = [&](int band, std::vector<std::int32_t>& values) {
    if (cells->GetRasterBand(band)->RasterIO(GF_Read, 0, 0, spec.width, spec.height, values.data(), spec.width,
                                             spec.height, GDT_Int32, 0, 0) != CE_None) {
      write_failure(path, "reading the degree raster");
    }
  };
  ZoneCounts counts;
  std::vector<std::int32_t> with_degree(hazard.size());
  for (std::size_t cell = 0; cell < hazard.size(); ++cell) with_degree[cell] = degree[cell] > 0 ? 1 : 0;
  counts.cell_patches = patches_of(degree, with_degree, spec.width, spec.height);
  if (generalisation.smooth) degree = majority_smoothed(degree, valid, spec.width, spec.height);
  write_band(1, degree);
  write_band(2, valid);
  // GDAL's sieve (gdal_sieve): a 4-connected patch of one degree (0 included, so small gaps
  // close too) of fewer cells than the minimum area joins its largest neighbouring patch.
  const double cell_area = std::abs(geotransform[1] * geotransform[5]);
  const int threshold = static_cast<int>(std::ceil(generalisation.minimum_area_m2 / cell_area));
  if (threshold > 1 &&
      GDALSieveFilter(cells->GetRasterBand(1), cells->GetRasterBand(2), cells->GetRasterBand(1), threshold, 4, nullptr,
                      nullptr, nullptr) != CE_None) {
    write_failure(path, "sieving the zones smaller than the minimum area");
  }
  read_band(1, degree);
  for (std::size_t cell = 0; cell < hazard.size(); ++cell) with_degree[cell] = valid[cell] != 0 && degree[cell] > 0 ? 1 : 0;
  write_band(3, with_degree);
  std::error_code error;
  std::filesystem::remove(path, error);
  CPLErrorReset();
  GDALDatasetUniquePtr dataset(gpkg->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!dataset) write_failure(path, "creating the GeoPackage");
  CPLErrorReset();
  try {
    OGRLayer& layer = create_vector_layer(*dataset, path, spec.crs_wkt, kLayer);
    check_written(dataset->StartTransaction(), path, "starting the transaction");
    if (GDALPolygonize(cells->GetRasterBand(1), cells->GetRasterBand(3), &layer, 0, nullptr, nullptr, nullptr) != CE_None) {
      write_failure(path, "joining the cells into polygons");
    }
    std::map<int, const HazardDegree*> by_value;
    for (const HazardDegree& d : matrix.degrees) by_value[d.value] = &d;
    layer.ResetReading();
    std::vector<std::unique_ptr<OGRFeature>> features;
    for (OGRFeature* feature = layer.GetNextFeature(); feature != nullptr; feature = layer.GetNextFeature()) {
      features.emplace_back(feature);
    }
    counts.zones = static_cast<long>(features.size());
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
  return counts;
}

}  // namespace

std::string hazard_style_qml(const HazardMatrix& matrix) {
  IntensityScheme palette;  // the paletted style of classes that intensity.tif uses
  for (const HazardDegree& d : matrix.degrees) palette.classes.push_back({d.value, d.name, d.label, d.colour, {}});
  return intensity_style_qml(palette);
}

ZoneCounts add_hazard_zones(LayerWriter& writer, const Grid<float>& hazard, const HazardMatrix& matrix,
                            const ZoneGeneralisation& generalisation) {
  const ZoneCounts counts = write_zones(writer.temporary_path("hazard_zones.gpkg"), hazard, matrix, generalisation);
  std::ofstream qml(writer.temporary_path("hazard_zones.qml"), std::ios::binary);
  qml << zones_style_qml(matrix);
  qml.close();
  if (!qml) throw std::runtime_error("cannot write " + (writer.folder() / "hazard_zones.qml").string());
  return counts;
}

}  // namespace talus::gis
