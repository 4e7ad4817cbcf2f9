// Output layers (DESIGN.md section 3): Float32 Cloud Optimized GeoTIFFs on the DEM's grid and
// CRS, one nodata value, band description and unit, software version and scenario in the
// metadata, statistics, and a QML style beside each so QGIS opens it styled.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "talus/core/grid.hpp"
#include "talus/gis/layer_overviews.hpp"

namespace talus::gis {

struct LayerDescription {
  std::string name;          // file stem, also the QML style's name in gis/styles
  std::string description;   // band description, e.g. "Reach probability"
  std::string unit;          // band unit, e.g. "kJ"; empty for counts and probabilities
  OverviewReduction overview = OverviewReduction::largest;  // how a zoomed-out cell sums up its cells
  std::string style_qml{};   // the layer's own QML style; empty: the one of gis/styles/<name>.qml
};

// Writes a set of layers into one folder as a unit: each layer goes to a temporary name and
// all are renamed only by commit(), so a failed run leaves no partial layer behind. Beside each
// <layer>.tif go <layer>.qml (its style) and <layer>.qmd (title and abstract for QGIS).
//
// Metadata keys the writer also reads: TALUS_PROCESS ("rock fall", "mud flow") ends each
// layer's title, so the two processes' layers of one quantity have distinct titles, and
// TALUS_SCENARIO goes into each abstract.
class LayerWriter {
 public:
  // metadata: written into every layer (TALUS_VERSION is added); the folder is created.
  LayerWriter(std::filesystem::path out_dir, std::map<std::string, std::string> metadata);
  ~LayerWriter();  // removes the temporary files of a set that was never committed
  LayerWriter(const LayerWriter&) = delete;
  LayerWriter& operator=(const LayerWriter&) = delete;

  // Writes values (nodata where invalid per the grid's spec) as a COG + its QML style and QMD.
  void add(const Grid<float>& values, const LayerDescription& layer);
  // Writes a non-raster file of the set (run.json, a GeoPackage) from its temporary path.
  std::filesystem::path temporary_path(const std::string& file_name);
  // Renames every temporary file to its final name.
  void commit();
  const std::filesystem::path& folder() const { return out_dir_; }

 private:
  std::filesystem::path out_dir_;
  std::map<std::string, std::string> metadata_;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> pending_;  // temp -> final
  std::string written_at_;  // UTC date and time of the set, for the layers' metadata
  bool committed_ = false;
};

// The QML style embedded from gis/styles/<layer>.qml, if there is one.
std::optional<std::string_view> embedded_style(std::string_view layer);

}  // namespace talus::gis
