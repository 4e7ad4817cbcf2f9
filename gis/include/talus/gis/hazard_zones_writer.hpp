// The hazard map of a study (issue 19, item 3; docs/study.md, "Hazard map"): hazard.tif's
// paletted style, and hazard_zones.gpkg, the map's cells of each degree joined into polygons
// (layer "hazard_zones": degree value, name and label), with a categorized style beside it.
#pragma once

#include <string>

#include "talus/core/grid.hpp"
#include "talus/gis/layer_writer.hpp"
#include "talus/hazard/hazard_matrix.hpp"

namespace talus::gis {

// The QML text of hazard.tif: a paletted renderer with the matrix's degrees (cells of 0, no
// hazard, transparent).
std::string hazard_style_qml(const HazardMatrix& matrix);

// Adds hazard_zones.gpkg and hazard_zones.qml to a layer set: one polygon per 4-connected patch of
// cells of one degree (cells of 0 and nodata make none), in the grid's CRS.
void add_hazard_zones(LayerWriter& writer, const Grid<float>& hazard, const HazardMatrix& matrix);

}  // namespace talus::gis
