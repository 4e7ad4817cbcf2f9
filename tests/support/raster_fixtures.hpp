// Small rasters and vector layers written to disk for the GIS and CLI tests.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace talus::test {

struct RasterFixture {
  int width = 40, height = 30;
  double x0 = 500000.0, y0 = 5200000.0, cell = 10.0;  // upper-left corner and cell size (m)
  std::string crs = "EPSG:32632";                      // any OGR user input; empty for none
  std::string unit;                                    // band unit type
  double nodata = -9999.0;
  bool integer = false;                                // Int16 instead of Float32
  std::function<double(int col, int row)> value = [](int, int row) { return 1000.0 - row; };
};

// Writes a GeoTIFF from the fixture.
void write_raster(const std::filesystem::path& path, const RasterFixture& fixture);

struct VectorFeature {
  std::string wkt;       // geometry in the layer's CRS
  double depth = 0;      // written when the layer has a depth field
};

// Band 1 of a raster as Float32, row by row; throws std::runtime_error when it cannot be read.
std::vector<float> read_band(const std::filesystem::path& path);

// Writes a GeoPackage with one layer of the given features.
void write_vector(const std::filesystem::path& path, const std::string& crs, const std::vector<VectorFeature>& features,
                  bool with_depth_field);

// A field of an attribute layer: real numbers, or text.
struct LayerField {
  std::string name;
  bool text = false;
};

// A feature of an attribute layer: its geometry (in the layer's CRS) and one value per field,
// std::nullopt for NULL; a real field's value is its text read as a number ("inf" is infinity).
struct LayerFeature {
  std::string wkt;
  std::vector<std::optional<std::string>> values;
};

// Writes a GeoPackage with one layer, "release", of the given fields and features.
void write_layer(const std::filesystem::path& path, const std::string& crs, const std::vector<LayerField>& fields,
                 const std::vector<LayerFeature>& features);

}  // namespace talus::test
