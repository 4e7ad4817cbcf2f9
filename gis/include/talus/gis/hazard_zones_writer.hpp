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

// How the zones generalise the map's cells (docs/study.md, "Hazard zones"): hazard.tif keeps
// every cell; the zones are the map a reader takes in at the scale of a hazard zone plan.
struct ZoneGeneralisation {
  double minimum_area_m2 = 400.0;  // m2: a patch of one degree smaller than this joins a neighbour
  bool smooth = true;              // a 3 x 3 majority filter before the patches are counted
};

// What the zones came to, for study.json: polygons before and after the generalisation.
struct ZoneCounts {
  long cell_patches = 0;  // 4-connected patches of one degree in the raw map
  long zones = 0;         // polygons written
};

// Adds hazard_zones.gpkg and hazard_zones.qml to a layer set: one polygon per 4-connected patch of
// cells of one degree after the generalisation (cells of 0 and nodata make none), in the grid's
// CRS; the residual degree is hatched.
ZoneCounts add_hazard_zones(LayerWriter& writer, const Grid<float>& hazard, const HazardMatrix& matrix,
                            const ZoneGeneralisation& generalisation);

}  // namespace talus::gis
