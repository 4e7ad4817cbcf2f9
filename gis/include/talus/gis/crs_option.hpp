// The --crs option (docs/architecture.md section 3): assigns a CRS to inputs that lack one or carry a
// wrong one. "EPSG:nnnn", any WKT or PROJ string OGR understands, or "local" for local metric
// coordinates with no CRS at all.
#pragma once

#include <string>

namespace talus::gis {

struct CrsOption {
  enum class Kind { from_file, assigned, local };
  Kind kind = Kind::from_file;
  std::string wkt;     // the assigned CRS as WKT (Kind::assigned)
  std::string text;    // what the user typed, for messages and run.json
};

// Parses the option text; an empty text means "use the files' own CRS". Throws InputError.
CrsOption parse_crs_option(const std::string& text);

}  // namespace talus::gis
