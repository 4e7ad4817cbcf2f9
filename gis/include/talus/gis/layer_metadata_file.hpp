// The QGIS layer metadata file (<layer>.qmd) written beside each layer: QGIS reads it when it
// opens <layer>.tif and shows its title, abstract, keywords and history in the layer's
// properties and in a print layout's metadata fields (docs/layers.md, "Metadata for QGIS").
#pragma once

#include <string>
#include <vector>

namespace talus::gis {

struct LayerMetadataText {
  std::string identifier;             // the file stem, e.g. "energy_max"
  std::string title;                  // e.g. "Maximum kinetic energy (rock fall)"
  std::string abstract;               // what the layer holds, its unit, the scenario and the run
  std::vector<std::string> keywords;  // e.g. {"rock fall", "hazard map", "Talus"}
  std::string history;                // the program and version that wrote it, and when
};

// The .qmd text in the format QGIS 3.22 saves with QgsMapLayer::saveNamedMetadata.
std::string qgis_layer_metadata(const LayerMetadataText& metadata);

}  // namespace talus::gis
