// QGIS paletted style of the intensity layer (intensity_style.hpp).
#include "talus/gis/intensity_style.hpp"

#include <algorithm>
#include <sstream>
#include <vector>

#include "talus/gis/xml_text.hpp"

namespace talus::gis {

std::string intensity_style_qml(const IntensityScheme& scheme) {
  std::vector<const IntensityClass*> classes;
  for (const IntensityClass& c : scheme.classes) classes.push_back(&c);
  std::ranges::sort(classes, {}, &IntensityClass::value);
  std::ostringstream qml;
  qml << "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n"
         "<qgis version=\"3.22.16-Białowieża\" styleCategories=\"AllStyleCategories\" hasScaleBasedVisibilityFlag=\"0\" "
         "maxScale=\"0\" minScale=\"1e+08\">\n"
         "  <flags>\n    <Identifiable>1</Identifiable>\n    <Removable>1</Removable>\n"
         "    <Searchable>1</Searchable>\n    <Private>0</Private>\n  </flags>\n"
         "  <pipe>\n    <provider>\n      <resampling maxOversampling=\"2\" zoomedInResamplingMethod=\"nearestNeighbour\" "
         "zoomedOutResamplingMethod=\"nearestNeighbour\" enabled=\"false\"/>\n    </provider>\n"
         "    <rasterrenderer type=\"paletted\" band=\"1\" alphaBand=\"-1\" nodataColor=\"\" opacity=\"0.8\">\n"
         "      <colorPalette>\n";
  for (const IntensityClass* c : classes) {
    qml << "        <paletteEntry color=\"" << xml_escaped(c->colour) << "\" alpha=\"255\" value=\"" << c->value
        << "\" label=\"" << xml_escaped(c->label) << "\"/>\n";
  }
  qml << "      </colorPalette>\n    </rasterrenderer>\n"
         "    <brightnesscontrast brightness=\"0\" contrast=\"0\" gamma=\"1\"/>\n"
         "    <huesaturation grayscaleMode=\"0\" colorizeGreen=\"128\" invertColors=\"0\" colorizeBlue=\"128\" "
         "colorizeRed=\"255\" saturation=\"0\" colorizeOn=\"0\" colorizeStrength=\"100\"/>\n"
         "    <rasterresampler maxOversampling=\"2\"/>\n    <resamplingStage>resamplingFilter</resamplingStage>\n"
         "  </pipe>\n  <blendMode>0</blendMode>\n</qgis>\n";
  return qml.str();
}

}  // namespace talus::gis
