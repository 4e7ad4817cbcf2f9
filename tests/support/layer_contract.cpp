#include "layer_contract.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace talus::test {
namespace {

namespace fs = std::filesystem;

struct LayerRule {
  const char* name;
  bool needs_unit;        // counts, probabilities and classes carry none
  bool may_be_negative;   // only a signed change of the ground
  bool optional;          // written only with an option (--erodible) or without one (--intensity none)
};

// docs/layers.md, "The layers".
const std::vector<LayerRule>& rules_for(const std::string& kind) {
  static const std::vector<LayerRule> rockfall = {
      {"reach_probability", false, false, false}, {"passages", false, false, false},
      {"source_count", false, false, false},      {"deposits", false, false, false},
      {"energy_max", true, false, false},         {"energy_p95", true, false, false},
      {"jump_height_p95", true, false, false},    {"velocity_max", true, false, false},
      {"energy_loss_friction", true, false, false}, {"energy_loss_deformation", true, false, false},
      {"intensity", false, false, true}};
  static const std::vector<LayerRule> mudflow = {
      {"flow_depth_max", true, false, false}, {"velocity_max", true, false, false},
      {"pressure_max", true, false, false},   {"deposit_depth", true, false, false},
      {"arrival_time", true, false, false},   {"erosion_depth", true, true, true},
      {"intensity", false, false, true}};
  if (kind == "rockfall") return rockfall;
  if (kind == "mudflow") return mudflow;
  throw std::invalid_argument("layer_contract_problems: kind must be rockfall or mudflow, not " + kind);
}

constexpr double kNodata = -9999.0;  // docs/layers.md, "The raster format"

struct DemGrid {
  int width = 0, height = 0;
  double geotransform[6] = {};
  OGRSpatialReference crs;
  bool has_crs = false;
};

DemGrid read_grid(const fs::path& dem) {
  GDALDatasetUniquePtr dataset(GDALDataset::Open(dem.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!dataset) throw std::runtime_error(dem.string() + ": the DEM does not open");
  DemGrid grid;
  grid.width = dataset->GetRasterXSize();
  grid.height = dataset->GetRasterYSize();
  dataset->GetGeoTransform(grid.geotransform);
  if (const OGRSpatialReference* crs = dataset->GetSpatialRef()) {
    grid.crs = *crs;
    grid.has_crs = true;
  }
  return grid;
}

bool same_geotransform(const double* a, const double* b) {
  for (int k = 0; k < 6; ++k) {
    if (std::abs(a[k] - b[k]) > 1e-6 * std::max(1.0, std::abs(b[k]))) return false;
  }
  return true;
}

// The checks of one raster layer: grid, CRS, type, nodata, band metadata, COG layout, sidecars,
// and its values inside the valid area (no NaN; no negative value but where the rule allows).
void check_raster(const LayerRule& rule, const fs::path& out, const DemGrid& dem, std::vector<std::string>& problems) {
  const std::string file = std::string(rule.name) + ".tif";
  const fs::path path = out / file;
  if (!fs::exists(path)) {
    if (!rule.optional) problems.push_back(file + ": missing");
    return;
  }
  GDALDatasetUniquePtr layer(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!layer) {
    problems.push_back(file + ": does not open as a raster");
    return;
  }
  if (layer->GetRasterXSize() != dem.width || layer->GetRasterYSize() != dem.height) {
    problems.push_back(file + ": " + std::to_string(layer->GetRasterXSize()) + " x " +
                       std::to_string(layer->GetRasterYSize()) + " cells, the DEM " + std::to_string(dem.width) +
                       " x " + std::to_string(dem.height));
  }
  double geotransform[6] = {};
  if (layer->GetGeoTransform(geotransform) != CE_None || !same_geotransform(geotransform, dem.geotransform)) {
    problems.push_back(file + ": its geotransform is not the DEM's");
  }
  const OGRSpatialReference* crs = layer->GetSpatialRef();
  if (dem.has_crs && (crs == nullptr || !crs->IsSame(&dem.crs))) problems.push_back(file + ": its CRS is not the DEM's");
  GDALRasterBand* band = layer->GetRasterBand(1);
  if (layer->GetRasterCount() != 1) problems.push_back(file + ": " + std::to_string(layer->GetRasterCount()) + " bands");
  if (band->GetRasterDataType() != GDT_Float32) {
    problems.push_back(file + ": type " + GDALGetDataTypeName(band->GetRasterDataType()) + ", not Float32");
  }
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  if (!has_nodata || nodata != kNodata) problems.push_back(file + ": nodata is not -9999");
  if (std::string(band->GetDescription()).empty()) problems.push_back(file + ": no band description");
  if (rule.needs_unit && std::string(band->GetUnitType()).empty()) problems.push_back(file + ": no unit");
  const char* layout = layer->GetMetadataItem("LAYOUT", "IMAGE_STRUCTURE");
  if (layout == nullptr || std::string(layout) != "COG") problems.push_back(file + ": not a Cloud Optimized GeoTIFF");
  for (const char* sidecar : {".qml", ".qmd"}) {
    if (!fs::exists(out / (std::string(rule.name) + sidecar))) {
      problems.push_back(std::string(rule.name) + sidecar + ": missing beside " + file);
    }
  }
  std::vector<float> values(static_cast<std::size_t>(layer->GetRasterXSize()) * layer->GetRasterYSize());
  if (band->RasterIO(GF_Read, 0, 0, layer->GetRasterXSize(), layer->GetRasterYSize(), values.data(),
                     layer->GetRasterXSize(), layer->GetRasterYSize(), GDT_Float32, 0, 0) != CE_None) {
    problems.push_back(file + ": its values cannot be read");
    return;
  }
  bool nan = false, negative = false;
  for (const float value : values) {
    if (value == static_cast<float>(kNodata)) continue;
    nan = nan || std::isnan(value);
    negative = negative || value < 0.0f;
  }
  if (nan) problems.push_back(file + ": NaN inside the valid area");
  if (negative && !rule.may_be_negative) problems.push_back(file + ": negative values");
}

// trajectories.gpkg: one layer of 3D lines with at least one feature.
void check_trajectories(const fs::path& out, std::vector<std::string>& problems) {
  const fs::path path = out / "trajectories.gpkg";
  if (!fs::exists(path)) {
    problems.push_back("trajectories.gpkg: missing");
    return;
  }
  GDALDatasetUniquePtr vectors(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!vectors || vectors->GetLayerCount() == 0) {
    problems.push_back("trajectories.gpkg: no layer");
    return;
  }
  OGRLayer* lines = vectors->GetLayer(0);
  if (lines->GetFeatureCount() == 0) problems.push_back("trajectories.gpkg: no trajectory");
  if (!OGR_GT_HasZ(lines->GetGeomType())) problems.push_back("trajectories.gpkg: its lines are not 3D");
}

void check_run_record(const fs::path& out, std::vector<std::string>& problems) {
  std::ifstream in(out / "run.json");
  if (!in) {
    problems.push_back("run.json: missing");
    return;
  }
  try {
    const nlohmann::json record = nlohmann::json::parse(in);
    for (const char* key : {"software", "version", "inputs", "parameters"}) {
      if (!record.contains(key)) problems.push_back(std::string("run.json: no \"") + key + "\"");
    }
  } catch (const nlohmann::json::parse_error& e) {
    problems.push_back(std::string("run.json: not JSON: ") + e.what());
  }
}

}  // namespace

std::vector<std::string> layer_contract_problems(const std::string& kind, const fs::path& out, const fs::path& dem) {
  GDALAllRegister();
  const auto& rules = rules_for(kind);
  const DemGrid grid = read_grid(dem);
  std::vector<std::string> problems;
  for (const LayerRule& rule : rules) check_raster(rule, out, grid, problems);
  if (kind == "rockfall") check_trajectories(out, problems);
  check_run_record(out, problems);
  return problems;
}

}  // namespace talus::test
