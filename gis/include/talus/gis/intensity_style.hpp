// The QGIS style of an intensity layer (docs/layers.md, "intensity.tif"): a paletted renderer
// with the guideline's classes, generated from the scheme because a user's guideline brings its
// own classes. Cells of 0 (not affected) are not in the palette, so QGIS leaves them transparent
// and the legend lists only the classes.
#pragma once

#include <string>

#include "talus/hazard/intensity_classes.hpp"

namespace talus::gis {

// The QML text, in the format QGIS 3.22 saves; the classes in rising order of value.
std::string intensity_style_qml(const IntensityScheme& scheme);

}  // namespace talus::gis
