// Parsing of the --crs option (docs/architecture.md section 3).
#include "talus/gis/crs_option.hpp"

#include <ogr_spatialref.h>

#include "talus/core/errors.hpp"
#include "talus/gis/gdal_dataset.hpp"

namespace talus::gis {

CrsOption parse_crs_option(const std::string& text) {
  CrsOption option;
  option.text = text;
  if (text.empty()) return option;
  if (text == "local" || text == "LOCAL") {
    option.kind = CrsOption::Kind::local;
    return option;
  }
  ensure_gdal_ready();
  OGRSpatialReference srs;
  if (srs.SetFromUserInput(text.c_str()) != OGRERR_NONE) {
    throw InputError("--crs " + text + ": not a CRS (use EPSG:nnnn, a WKT string, or local)");
  }
  if (srs.IsGeographic()) {
    throw InputError("--crs " + text + ": a geographic CRS (degrees); give the projected CRS the files are in");
  }
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT2_2019", nullptr};
  srs.exportToWkt(&wkt, options);
  option.wkt = wkt;
  CPLFree(wkt);
  option.kind = CrsOption::Kind::assigned;
  return option;
}

}  // namespace talus::gis
