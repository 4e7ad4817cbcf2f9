// The rock-fall conditions of a release raster's cells (release_raster_conditions.hpp): each
// attribute band is copied alone into a temporary file, aligned onto the DEM's grid as any input raster
// is, and each release cell's values go through the same reading and checks as a vector
// feature's attributes, as the fields of a feature built for the cell.
#include "talus/gis/release_raster_conditions.hpp"

#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogr_feature.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "talus/core/errors.hpp"
#include "talus/gis/gdal_dataset.hpp"
#include "talus/gis/raster_alignment.hpp"
#include "talus/gis/release_attributes.hpp"

namespace talus::gis {
namespace {

// The attributes a band may carry, as the vector attributes of docs/inputs.md; `shape` as a
// code, `block_size` as one diameter.
constexpr std::array<const char*, 8> kBandAttributes{"shape", "block_size", "density", "mass",
                                                     "vx",    "vy",         "vz",      "release_height"};
constexpr std::array<const char*, 3> kShapeCodes{"sphere", "ellipsoid", "box"};  // codes 1, 2, 3

// The text in lower case without leading and trailing blanks.
std::string normalized(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  std::string trimmed = text.substr(first, text.find_last_not_of(" \t") - first + 1);
  std::transform(trimmed.begin(), trimmed.end(), trimmed.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return trimmed;
}

struct AttributeBand {
  int band = 0;          // 1-based in the file
  std::string name;      // one of kBandAttributes
  Grid<double> values;   // on the DEM's grid
};

// Band `band` of `dataset` alone, as a temporary GeoTIFF that align_raster reads like any input.
std::string single_band_copy(GDALDataset& dataset, int band, const std::string& name) {
  const std::string copy = (std::filesystem::temp_directory_path() /
                            ("talus-release-" + std::to_string(::getpid()) + "-band-" + std::to_string(band) + ".tif"))
                               .string();
  const std::string number = std::to_string(band);
  const char* arguments[] = {"-b", number.c_str(), "-of", "GTiff", nullptr};
  GDALTranslateOptions* options = GDALTranslateOptionsNew(const_cast<char**>(arguments), nullptr);
  int failed = 0;
  GDALDatasetH result = GDALTranslate(copy.c_str(), GDALDataset::ToHandle(&dataset), options, &failed);
  GDALTranslateOptionsFree(options);
  if (result == nullptr || failed != 0) {
    throw InputError(name + ": band " + number + " cannot be read: " + last_gdal_error("GDAL error"));
  }
  GDALClose(result);
  return copy;
}

// The bands after the first, each of which must name an attribute, aligned onto `dem`.
std::vector<AttributeBand> attribute_bands(const std::filesystem::path& path, const GridSpec& dem, const CrsOption& crs,
                                           const std::string& name) {
  GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!dataset) throw InputError(name + ": not a raster GDAL can read");
  std::vector<AttributeBand> bands;
  for (int band = 2; band <= dataset->GetRasterCount(); ++band) {
    const std::string description = normalized(dataset->GetRasterBand(band)->GetDescription());
    const auto known = std::find(kBandAttributes.begin(), kBandAttributes.end(), description);
    if (known == kBandAttributes.end()) {
      throw InputError(name + ": band " + std::to_string(band) + " is described as '" + description +
                       "', not as a release attribute; name it shape, block_size, density, mass, vx, vy, vz or "
                       "release_height (band 1 holds the release cells)");
    }
    const std::string copy = single_band_copy(*dataset, band, name);
    AlignedRaster aligned;
    try {
      aligned = align_raster(copy, "release", dem, ValueKind::classes, crs);
    } catch (...) {
      std::filesystem::remove(copy);
      throw;
    }
    std::filesystem::remove(copy);
    bands.push_back({band, *known, std::move(aligned.values)});
  }
  return bands;
}

}  // namespace

void add_raster_conditions(const std::filesystem::path& path, const GridSpec& dem, const CrsOption& crs,
                           const Rock& run_rock, ReleaseSet& release) {
  const std::string name = describe_input(path, "release");
  const std::vector<AttributeBand> bands = attribute_bands(path, dem, crs, name);
  if (bands.empty()) return;
  // A feature definition is reference-counted: held here, released when the last feature and
  // this function are done with it.
  OGRFeatureDefn* definition = new OGRFeatureDefn("cell");
  definition->Reference();
  const std::unique_ptr<OGRFeatureDefn, void (*)(OGRFeatureDefn*)> held(definition, [](OGRFeatureDefn* d) { d->Release(); });
  for (const AttributeBand& band : bands) {
    OGRFieldDefn field(band.name.c_str(), band.name == "shape" ? OFTString : OFTReal);
    definition->AddFieldDefn(&field);
  }
  Grid<int> index_of_cell(release.depth.spec(), 0);
  const GridSpec& spec = release.depth.spec();
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) {
      if (!(release.depth.at(col, row) > 0.0f)) continue;
      const std::string where = name + ": cell (column " + std::to_string(col + 1) + ", row " + std::to_string(row + 1) + ")";
      OGRFeature feature(definition);
      for (std::size_t k = 0; k < bands.size(); ++k) {
        if (!bands[k].values.is_valid(col, row)) continue;
        const double value = bands[k].values.at(col, row);
        if (bands[k].name != "shape") {
          feature.SetField(static_cast<int>(k), value);
          continue;
        }
        const double code = std::round(value);
        if (code != value || code < 1 || code > 3) {
          std::ostringstream text;
          text << where << ": shape " << value << ": use 1 (sphere), 2 (ellipsoid) or 3 (box)";
          throw InputError(text.str());
        }
        feature.SetField(static_cast<int>(k), kShapeCodes[static_cast<std::size_t>(code) - 1]);
      }
      const ReleaseConditions conditions = read_release_conditions(feature, run_rock, where);
      if (conditions.empty()) continue;
      release.condition_sets.push_back(conditions);
      index_of_cell.at(col, row) = static_cast<int>(release.condition_sets.size());
    }
  }
  if (!release.condition_sets.empty()) release.condition_set_of_cell = std::move(index_of_cell);
}

}  // namespace talus::gis
