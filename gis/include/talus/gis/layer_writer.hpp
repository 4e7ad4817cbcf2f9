// Output layers (docs/architecture.md section 3): Float32 Cloud Optimized GeoTIFFs on the DEM's grid and
// CRS, one nodata value, band description and unit, software version and scenario in the
// metadata, statistics, and a QML style beside each so QGIS opens it styled.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "talus/core/grid.hpp"
#include "talus/gis/layer_overviews.hpp"
#include "talus/gis/staged_folder.hpp"

namespace talus::gis {

struct LayerDescription {
  std::string name;          // file stem, also the QML style's name in gis/styles
  std::string description;   // band description, e.g. "Reach probability"
  std::string unit;          // band unit, e.g. "kJ"; empty for counts and probabilities
  OverviewReduction overview = OverviewReduction::largest;  // how a zoomed-out cell sums up its cells
  std::string style_qml{};   // the layer's own QML style; empty: the one of gis/styles/<name>.qml
};

// Writes a set of layers into one folder as a unit: every file goes into a staging folder
// beside the output folder (staged_folder.hpp), which commit() swaps in whole, so a failed or
// killed run leaves the old set as it was. Beside each <layer>.tif go <layer>.qml (its style) and
// <layer>.qmd (title and abstract for QGIS).
//
// Metadata keys the writer also reads: TALUS_PROCESS ("rock fall", "mud flow") ends each
// layer's title, so the two processes' layers of one quantity have distinct titles,
// TALUS_SCENARIO goes into each abstract, and so does TALUS_MISSING_TRAJECTORIES, when it is not
// "0", with TALUS_TRAJECTORIES: the trajectories a rock fall lost to numerical failures.
class LayerWriter {
 public:
  // metadata: written into every layer (TALUS_VERSION is added). The output folder is checked
  // and the staging folder created here (InputError naming the folder when that fails), so a
  // command constructs its writer before any work.
  LayerWriter(const std::filesystem::path& out_dir, std::map<std::string, std::string> metadata);
  LayerWriter(const LayerWriter&) = delete;
  LayerWriter& operator=(const LayerWriter&) = delete;

  // Sets one metadata item of the layers added after this call.
  void set_metadata(const std::string& key, const std::string& value) { metadata_[key] = value; }
  // Writes values (nodata where invalid per the grid's spec) as a COG + its QML style and QMD.
  void add(const Grid<float>& values, const LayerDescription& layer);
  // Where a non-raster file of the set (run.json, a GeoPackage) is written before the commit;
  // each name once.
  std::filesystem::path temporary_path(const std::string& file_name);
  // Puts the staged set in the output folder's place.
  void commit();
  const std::filesystem::path& folder() const { return staged_.out(); }
  // The folder the set is written into until commit().
  const std::filesystem::path& staging_folder() const { return staged_.staging(); }

 private:
  StagedFolder staged_;
  std::map<std::string, std::string> metadata_;
  std::set<std::string> names_;  // the files of the set
  std::string written_at_;       // UTC date and time of the set, for the layers' metadata
};

// The QML style embedded from gis/styles/<layer>.qml, if there is one.
std::optional<std::string_view> embedded_style(std::string_view layer);

}  // namespace talus::gis
