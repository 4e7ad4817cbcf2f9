// LayerWriter: builds each layer in a GDAL MEM dataset (Float32, nodata -9999, description, unit,
// metadata, exact statistics) and copies it with the COG driver to a hidden temporary name beside
// its QML style and QGIS metadata; commit() renames the set. docs/layers.md describes the format.
#include "talus/gis/layer_writer.hpp"

#include <cpl_error.h>
#include <gdal_priv.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "talus/core/errors.hpp"
#include "talus/gis/gdal_dataset.hpp"
#include "talus/gis/layer_metadata_file.hpp"

namespace talus::gis {
namespace {

// The one nodata value of every layer, whatever the DEM used: cells outside its valid area.
constexpr double kLayerNodata = -9999.0;

// COG with DEFLATE and the floating-point predictor (TIFF predictor 3 for Float32) on the full
// resolution and on the overviews, which are the in-memory dataset's own (fill_overviews);
// 256-pixel tiles.
constexpr int kTileSize = 256;
constexpr std::array kCogOptions{"COMPRESS=DEFLATE",
                                 "PREDICTOR=YES",
                                 "OVERVIEW_COMPRESS=DEFLATE",
                                 "OVERVIEW_PREDICTOR=YES",
                                 "OVERVIEWS=FORCE_USE_EXISTING",
                                 "BLOCKSIZE=256",
                                 static_cast<const char*>(nullptr)};

GDALDriver& driver(const char* name) {
  ensure_gdal_ready();
  GDALDriver* found = GetGDALDriverManager()->GetDriverByName(name);
  if (found == nullptr) throw std::runtime_error(std::string("GDAL has no ") + name + " driver");
  return *found;
}

// Throws a one-line error naming the layer, with GDAL's last message.
[[noreturn]] void gdal_failure(const std::filesystem::path& layer, const std::string& step) {
  throw std::runtime_error("cannot write " + layer.string() + ": " + last_gdal_error(step + " failed"));
}

void check(CPLErr result, const std::filesystem::path& layer, const std::string& step) {
  if (result != CE_None) gdal_failure(layer, step);
}

std::string band_description(const LayerDescription& layer) {
  return layer.unit.empty() ? layer.description : layer.description + " (" + layer.unit + ")";
}

// The title and abstract QGIS shows for the layer (layer_metadata_file.hpp).
LayerMetadataText layer_metadata(const LayerDescription& layer, const std::map<std::string, std::string>& metadata,
                                 const std::string& written_at) {
  const auto item = [&](const char* key) {
    const auto found = metadata.find(key);
    return found == metadata.end() ? std::string() : found->second;
  };
  const std::string process = item("TALUS_PROCESS");
  LayerMetadataText text;
  text.identifier = layer.name;
  text.title = process.empty() ? layer.description : layer.description + " (" + process + ")";
  text.abstract = band_description(layer) + (process.empty() ? "" : ", " + process + " hazard layer") +
                  " written by Talus " + TALUS_VERSION + " on " + written_at + ".";
  if (const std::string scenario = item("TALUS_SCENARIO"); !scenario.empty()) text.abstract += " Scenario: " + scenario + ".";
  if (const std::string missing = item("TALUS_MISSING_TRAJECTORIES"); !missing.empty() && missing != "0") {
    text.abstract += " Missing: " + missing + " of the run's " + item("TALUS_TRAJECTORIES") +
                     " trajectories failed numerically and are not in this layer (run.json, recovery).";
  }
  text.abstract += " Cells never reached are 0, cells outside the DEM's valid area nodata; run.json beside the layer "
                   "records every input and parameter.";
  text.keywords = {"Talus", "natural hazards"};
  if (!process.empty()) text.keywords.push_back(process);
  text.history = "Talus " + std::string(TALUS_VERSION) + ", " + written_at;
  return text;
}

// Now as an ISO 8601 UTC date and time, e.g. 2026-12-02T06:40:00Z.
std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// The layer in memory: values, georeferencing, band properties, metadata and statistics.
GDALDatasetUniquePtr in_memory(const Grid<float>& values, const LayerDescription& layer,
                               const std::map<std::string, std::string>& metadata,
                               const std::filesystem::path& final_path) {
  const GridSpec& spec = values.spec();
  GDALDatasetUniquePtr dataset(driver("MEM").Create("", spec.width, spec.height, 1, GDT_Float32, nullptr));
  if (!dataset) gdal_failure(final_path, "creating the in-memory dataset");
  std::array<double, 6> geotransform = spec.own_geotransform();
  check(dataset->SetGeoTransform(geotransform.data()), final_path, "setting the geotransform");
  if (!spec.crs_wkt.empty())
    check(dataset->SetProjection(spec.crs_wkt.c_str()), final_path, "setting the CRS from its WKT");
  for (const auto& [key, value] : metadata)
    check(dataset->SetMetadataItem(key.c_str(), value.c_str()), final_path, "setting the metadata");

  GDALRasterBand* band = dataset->GetRasterBand(1);
  bool any_valid = false;
  std::vector<float> row(static_cast<std::size_t>(spec.width));
  for (int r = 0; r < spec.height; ++r) {
    for (int c = 0; c < spec.width; ++c) {
      const bool valid = values.is_valid(values.index(c, r));
      any_valid = any_valid || valid;
      row[static_cast<std::size_t>(c)] = valid ? values.at(c, r) : static_cast<float>(kLayerNodata);
    }
    check(band->RasterIO(GF_Write, 0, r, spec.width, 1, row.data(), spec.width, 1, GDT_Float32, 0, 0, nullptr),
          final_path, "writing the values");
  }
  check(band->SetNoDataValue(kLayerNodata), final_path, "setting nodata");
  // The unit goes into the description too: QGIS heads a layer's legend with it.
  band->SetDescription(band_description(layer).c_str());
  check(band->SetUnitType(layer.unit.c_str()), final_path, "setting the unit");
  // Exact statistics land in the band's STATISTICS_* metadata; GDAL has none to give without a
  // valid cell, and QGIS computes its own then.
  if (any_valid) {
    double min = 0, max = 0, mean = 0, stddev = 0;
    check(band->ComputeStatistics(FALSE, &min, &max, &mean, &stddev, nullptr, nullptr), final_path,
          "computing statistics");
  }
  return dataset;
}

// The overviews of the layer in memory, each cell the layer's reduction of the cells it covers
// (layer_overviews.hpp), so that no zoomed-out or printed view lowers a maximum.
void fill_overviews(GDALDataset& dataset, const Grid<float>& values, const LayerDescription& layer,
                    const std::filesystem::path& final_path) {
  std::vector<int> factors = overview_factors(values.spec().width, values.spec().height, kTileSize);
  if (factors.empty()) return;
  check(dataset.BuildOverviews("NONE", static_cast<int>(factors.size()), factors.data(), 0, nullptr, nullptr, nullptr),
        final_path, "creating the overviews");
  GDALRasterBand* band = dataset.GetRasterBand(1);
  for (std::size_t k = 0; k < factors.size(); ++k) {
    GDALRasterBand* overview = band->GetOverview(static_cast<int>(k));
    if (overview == nullptr) gdal_failure(final_path, "creating the overviews");
    std::vector<float> reduced =
        reduced_overview(values, factors[k], layer.overview, static_cast<float>(kLayerNodata));
    const int width = overview->GetXSize(), height = overview->GetYSize();
    if (static_cast<std::size_t>(width) * static_cast<std::size_t>(height) != reduced.size())
      gdal_failure(final_path, "sizing the overviews");
    check(overview->RasterIO(GF_Write, 0, 0, width, height, reduced.data(), width, height, GDT_Float32, 0, 0, nullptr),
          final_path, "writing the overviews");
    check(overview->SetNoDataValue(kLayerNodata), final_path, "setting the overviews' nodata");
  }
}

void write_text(const std::filesystem::path& path, std::string_view text, const std::filesystem::path& final_path) {
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw std::runtime_error("cannot write " + final_path.string());
}

void remove_quietly(const std::filesystem::path& path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}

}  // namespace

LayerWriter::LayerWriter(const std::filesystem::path& out_dir, std::map<std::string, std::string> metadata)
    : staged_(out_dir), metadata_(std::move(metadata)), written_at_(utc_now()) {
  metadata_["TALUS_VERSION"] = TALUS_VERSION;
}

std::filesystem::path LayerWriter::temporary_path(const std::string& file_name) {
  if (!names_.insert(file_name).second) throw std::logic_error("layer set already has " + file_name);
  return staged_.staging() / file_name;
}

void LayerWriter::add(const Grid<float>& values, const LayerDescription& layer) {
  const auto style = layer.style_qml.empty() ? embedded_style(layer.name) : std::string_view(layer.style_qml);
  if (!style) throw std::logic_error("no QML style in gis/styles for layer " + layer.name);
  const auto final_path = folder() / (layer.name + ".tif");
  const auto tif = temporary_path(layer.name + ".tif");
  const auto qml = temporary_path(layer.name + ".qml");
  const auto qmd = temporary_path(layer.name + ".qmd");
  CPLErrorReset();
  try {
    const auto dataset = in_memory(values, layer, metadata_, final_path);
    fill_overviews(*dataset, values, layer, final_path);
    GDALDatasetUniquePtr written(driver("COG").CreateCopy(tif.c_str(), dataset.get(), FALSE,
                                                          const_cast<char**>(kCogOptions.data()), nullptr, nullptr));
    const bool copied = written != nullptr;
    written.reset();  // closes the file; GDAL 3.6 reports a failed close through the error state only
    if (!copied || CPLGetLastErrorType() == CE_Failure) gdal_failure(final_path, "writing the Cloud Optimized GeoTIFF");
    write_text(qml, *style, folder() / (layer.name + ".qml"));
    write_text(qmd, qgis_layer_metadata(layer_metadata(layer, metadata_, written_at_)), folder() / (layer.name + ".qmd"));
  } catch (...) {
    for (const auto& path : {tif, qml, qmd}) {
      remove_quietly(path);
      names_.erase(path.filename().string());
    }
    throw;
  }
}

void LayerWriter::commit() { staged_.commit(); }

}  // namespace talus::gis
