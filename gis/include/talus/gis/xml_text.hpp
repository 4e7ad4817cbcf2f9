// Text placed inside the XML files Talus writes for QGIS (styles, layer definitions, metadata).
#pragma once

#include <string>
#include <string_view>

namespace talus::gis {

// `text` with the five XML special characters escaped, for element text and attribute values.
std::string xml_escaped(std::string_view text);

}  // namespace talus::gis
