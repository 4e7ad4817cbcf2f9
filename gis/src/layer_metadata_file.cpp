// QGIS layer metadata (.qmd) text for each written layer (layer_metadata_file.hpp).
#include "talus/gis/layer_metadata_file.hpp"

#include <sstream>

#include "talus/gis/xml_text.hpp"

namespace talus::gis {

std::string qgis_layer_metadata(const LayerMetadataText& metadata) {
  std::ostringstream qmd;
  qmd << "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n<qgis version=\"3.22.16-Białowieża\">\n"
      << "  <identifier>" << xml_escaped(metadata.identifier) << "</identifier>\n"
      << "  <parentidentifier></parentidentifier>\n  <language>en</language>\n  <type>dataset</type>\n"
      << "  <title>" << xml_escaped(metadata.title) << "</title>\n"
      << "  <abstract>" << xml_escaped(metadata.abstract) << "</abstract>\n";
  if (!metadata.keywords.empty()) {
    qmd << "  <keywords vocabulary=\"theme\">\n";
    for (const auto& keyword : metadata.keywords) qmd << "    <keyword>" << xml_escaped(keyword) << "</keyword>\n";
    qmd << "  </keywords>\n";
  }
  qmd << "  <links/>\n  <history>" << xml_escaped(metadata.history) << "</history>\n"
      << "  <fees></fees>\n  <encoding></encoding>\n  <crs/>\n  <extent/>\n</qgis>\n";
  return qmd.str();
}

}  // namespace talus::gis
