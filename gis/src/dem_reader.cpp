// DEM reading with the CRS rules of docs/architecture.md section 3.
#include "talus/gis/dem_reader.hpp"

#include <unistd.h>

#include <gdal_alg.h>
#include <gdal_utils.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <sstream>

#include "talus/core/errors.hpp"
#include "talus/gis/gdal_dataset.hpp"

namespace talus::gis {
namespace {

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool is_metre_unit(const std::string& unit) {
  const std::string u = lowercase(unit);
  return u.empty() || u == "m" || u == "metre" || u == "meter" || u == "metres" || u == "meters";
}

std::string format_extent(const GridSpec& spec) {
  const auto& gt = spec.geotransform;
  std::ostringstream text;
  text.precision(10);
  text << "x " << gt[0] << " .. " << gt[0] + spec.width * gt[1] << ", y " << gt[3] + spec.height * gt[5]
       << " .. " << gt[3];
  return text.str();
}

// Coordinates that cannot be degrees: the CRS contradicts them.
bool coordinates_fit_degrees(const GridSpec& spec) {
  const auto& gt = spec.geotransform;
  const double x0 = gt[0], x1 = gt[0] + spec.width * gt[1];
  const double y0 = gt[3] + spec.height * gt[5], y1 = gt[3];
  return x0 >= -180.0 && x1 <= 360.0 && y0 >= -90.0 && y1 <= 90.0;
}

// UTM zone (WGS 84) containing the centre of a geographic grid, as an EPSG code.
int utm_epsg_for(const GridSpec& spec) {
  const double lon = spec.geotransform[0] + 0.5 * spec.width * spec.geotransform[1];
  const double lat = spec.geotransform[3] + 0.5 * spec.height * spec.geotransform[5];
  const double wrapped = std::fmod(lon + 180.0, 360.0);
  const int zone = std::clamp(static_cast<int>(std::floor((wrapped < 0 ? wrapped + 360.0 : wrapped) / 6.0)) + 1, 1, 60);
  return (lat >= 0 ? 32600 : 32700) + zone;
}

// At most this many times the input's cells in the reprojected grid: a DEM in degrees that grows
// more than that in UTM spans too much of the Earth for one zone (docs/inputs.md, "DEM").
constexpr double kLargestReprojectionGrowth = 4.0;

// Refuses a reprojection whose grid (GDAL's suggested output, computed before any warping) would
// hold more than kLargestReprojectionGrowth times the input's cells.
void require_bounded_reprojection(GDALDataset& source, const std::string& name, const std::string& target) {
  const std::string destination = "DST_SRS=" + target;
  const char* options[] = {destination.c_str(), nullptr};
  void* transformer = GDALCreateGenImgProjTransformer2(GDALDataset::ToHandle(&source), nullptr,
                                                       const_cast<char**>(options));
  if (transformer == nullptr) throw InputError(name + ": reprojection to " + target + " failed: " + last_gdal_error("GDAL error"));
  double geotransform[6];
  int width = 0, height = 0;
  const CPLErr status = GDALSuggestedWarpOutput(GDALDataset::ToHandle(&source), GDALGenImgProjTransform, transformer,
                                                geotransform, &width, &height);
  GDALDestroyGenImgProjTransformer(transformer);
  if (status != CE_None) throw InputError(name + ": reprojection to " + target + " failed: " + last_gdal_error("GDAL error"));
  const double input = static_cast<double>(source.GetRasterXSize()) * source.GetRasterYSize();
  const double output = static_cast<double>(width) * height;
  if (output > kLargestReprojectionGrowth * input) {
    std::ostringstream message;
    message.precision(3);
    message << name << ": in degrees, reprojected to " << target << " it would need " << width << " x " << height
            << " cells, " << output / input << " times its own " << source.GetRasterXSize() << " x "
            << source.GetRasterYSize() << ": it spans too much of the Earth for one UTM zone; reproject it to a "
            << "projected CRS in metres first (gdalwarp -t_srs EPSG:nnnn)";
    throw InputError(message.str());
  }
}

// Reprojects a geographic dataset to a UTM zone in memory (bilinear, square cells).
GDALDatasetUniquePtr reproject_to_utm(GDALDataset& source, const std::string& name, int epsg) {
  const std::string target = "EPSG:" + std::to_string(epsg);
  require_bounded_reprojection(source, name, target);
  const char* arguments[] = {"-of", "MEM", "-t_srs", target.c_str(), "-r", "bilinear", "-dstnodata", "-9999", nullptr};
  GDALWarpAppOptions* options = GDALWarpAppOptionsNew(const_cast<char**>(arguments), nullptr);
  GDALDatasetH source_handle = GDALDataset::ToHandle(&source);
  int usage_error = 0;
  CPLErrorReset();
  GDALDatasetH warped = GDALWarp("", nullptr, 1, &source_handle, options, &usage_error);
  GDALWarpAppOptionsFree(options);
  if (warped == nullptr) throw InputError(name + ": reprojection to " + target + " failed: " + last_gdal_error("GDAL warp error"));
  return GDALDatasetUniquePtr(GDALDataset::FromHandle(warped));
}

// Cells of exactly 0 m connected to the border, in a DEM whose other elevations all lie above
// 1 m: exports such as the Norwegian MoT-Voellmy examples pad their DEMs this way.
std::size_t mark_zero_border_as_nodata(Grid<double>& dem) {
  const int w = dem.width(), h = dem.height();
  double lowest_nonzero = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < dem.size(); ++i) {
    if (dem.is_valid(i) && dem[i] != 0.0) lowest_nonzero = std::min(lowest_nonzero, dem[i]);
  }
  if (!(lowest_nonzero > 1.0)) return 0;  // terrain reaching 0 m (a coast): zeros may be real
  std::deque<std::pair<int, int>> queue;
  for (int c = 0; c < w; ++c) {
    queue.emplace_back(c, 0);
    queue.emplace_back(c, h - 1);
  }
  for (int r = 0; r < h; ++r) {
    queue.emplace_back(0, r);
    queue.emplace_back(w - 1, r);
  }
  std::size_t marked = 0;
  while (!queue.empty()) {
    const auto [c, r] = queue.front();
    queue.pop_front();
    if (!dem.spec().contains_cell(c, r) || dem.at(c, r) != 0.0) continue;
    dem.at(c, r) = input_nodata;
    ++marked;
    queue.emplace_back(c + 1, r);
    queue.emplace_back(c - 1, r);
    queue.emplace_back(c, r + 1);
    queue.emplace_back(c, r - 1);
  }
  return marked;
}

void require_metre_units(const OGRSpatialReference& srs, GDALRasterBand& band, const std::string& name) {
  const char* unit_name = nullptr;
  if (srs.IsProjected()) {
    const double factor = srs.GetLinearUnits(&unit_name);
    if (std::abs(factor - 1.0) > 1e-9) {
      throw InputError(name + ": horizontal unit is " + std::string(unit_name ? unit_name : "not metres") +
                       "; reproject it to a CRS in metres");
    }
  }
  if (srs.IsCompound() || srs.IsVertical()) {
    const double factor = srs.GetTargetLinearUnits("VERT_CS", &unit_name);
    if (std::abs(factor - 1.0) > 1e-9) {
      throw InputError(name + ": vertical unit is " + std::string(unit_name ? unit_name : "unknown") + ", not metres");
    }
  }
  const std::string band_unit = band.GetUnitType() ? band.GetUnitType() : "";
  if (!is_metre_unit(band_unit)) {
    throw InputError(name + ": vertical unit is '" + band_unit + "', not metres; convert the elevations to metres");
  }
}

// Elevations on Earth (m): from the deepest sea floor (Challenger Deep, about -10,935 m) to the
// highest summit (Everest, 8,849 m), rounded out (docs/inputs.md, "Plausible terrain").
constexpr double kLowestElevation = -11000.0;
constexpr double kHighestElevation = 9000.0;
// Cell sizes (m) Talus accepts: from survey-grade lidar to the coarsest global DEMs and beyond.
constexpr double kSmallestCell = 0.01;
constexpr double kLargestCell = 10000.0;
// Coordinates (m) beyond this lie off any projected CRS of the Earth (its circumference is 4e7 m).
constexpr double kLargestCoordinate = 1e8;

// The grid's georeferencing is one of a DEM on Earth: cell sizes and corner coordinates in range,
// and an elevation grid that fits in this machine's memory.
void require_plausible_grid(const GridSpec& spec, const std::string& name) {
  const double dx = std::abs(spec.geotransform[1]), dy = std::abs(spec.geotransform[5]);
  if (!(dx >= kSmallestCell && dx <= kLargestCell && dy >= kSmallestCell && dy <= kLargestCell)) {
    std::ostringstream message;
    message << name << ": cells of " << dx << " x " << dy << " m; expected " << kSmallestCell << "-" << kLargestCell
            << " m (are the coordinates in metres?)";
    throw InputError(message.str());
  }
  const double corners[] = {spec.geotransform[0], spec.geotransform[3],
                            spec.geotransform[0] + spec.width * spec.geotransform[1],
                            spec.geotransform[3] + spec.height * spec.geotransform[5]};
  for (const double c : corners) {
    if (!(std::abs(c) <= kLargestCoordinate)) {
      std::ostringstream message;
      message << name << ": a corner coordinate of " << c << " m lies beyond " << kLargestCoordinate
              << " m, off any projected CRS of the Earth";
      throw InputError(message.str());
    }
  }
  const double bytes = static_cast<double>(spec.cell_count()) * sizeof(double);
  const double memory = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  if (memory > 0 && bytes > memory) {
    std::ostringstream message;
    message.precision(3);
    message << name << ": " << spec.width << " x " << spec.height << " cells need " << bytes / 1e9
            << " GB for the elevations alone, more than this machine's " << memory / 1e9 << " GB of memory";
    throw InputError(message.str());
  }
}

// Elevations outside kLowestElevation-kHighestElevation cannot be terrain. When they all hold one
// value, it is an undeclared nodata value (ESRI's -3.4028235e38, say) and they become nodata (a
// note says so); mixed impossible values are refused.
void treat_impossible_elevations(std::vector<double>& values, double nodata, const std::string& name,
                                 std::vector<std::string>& notes) {
  std::size_t count = 0;
  double first = 0.0;
  bool one_value = true;
  for (const double v : values) {
    if (v == nodata || (v >= kLowestElevation && v <= kHighestElevation)) continue;
    if (count == 0) first = v;
    one_value = one_value && v == first;
    ++count;
  }
  if (count == 0) return;
  std::ostringstream text;
  text.precision(9);
  if (!one_value) {
    text << name << ": " << count << " cells hold elevations outside " << kLowestElevation << " to "
         << kHighestElevation << " m (" << first << " m, and others), impossible on Earth; declare the nodata value "
         << "or convert the elevations to metres";
    throw InputError(text.str());
  }
  for (double& v : values)
    if (v == first) v = nodata;
  text << count << " cells of elevation " << first << " m (impossible on Earth, an undeclared nodata value) taken as nodata";
  notes.push_back(text.str());
}

}  // namespace

std::string crs_display_name(const std::string& wkt) {
  if (wkt.empty()) return "local (no CRS)";
  OGRSpatialReference srs;
  if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return "unknown CRS";
  std::string name = srs.GetName() ? srs.GetName() : "unnamed CRS";
  srs.AutoIdentifyEPSG();
  const char* authority = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (authority && code) name += " (" + std::string(authority) + ":" + code + ")";
  return name;
}

DemInput read_dem(const std::filesystem::path& path, const CrsOption& crs) {
  const std::string name = describe_input(path, "DEM");
  GDALDatasetUniquePtr dataset = open_raster(path, "DEM");
  GridSpec spec = raster_grid(*dataset, name);
  DemInput result;

  OGRSpatialReference srs;
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  switch (crs.kind) {
    case CrsOption::Kind::local:
      result.notes.push_back("CRS: local metric coordinates (--crs local)");
      break;
    case CrsOption::Kind::assigned:
      srs.importFromWkt(crs.wkt.c_str());
      result.notes.push_back("CRS assigned by --crs " + crs.text);
      break;
    case CrsOption::Kind::from_file: {
      const OGRSpatialReference* file_srs = dataset->GetSpatialRef();
      if (file_srs == nullptr || file_srs->IsEmpty()) {
        throw InputError(name + ": has no CRS; give it with --crs EPSG:nnnn, --crs WKT or --crs local");
      }
      refuse_geocentric_crs(file_srs, name);
      srs = *file_srs;
      srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
      if (srs.IsGeographic() && !coordinates_fit_degrees(spec)) {
        throw InputError(name + ": its CRS is geographic (degrees) but its coordinates (" + format_extent(spec) +
                         ") are metres; give the right CRS with --crs");
      }
      break;
    }
  }
  if (const char* area = dataset->GetMetadataItem(GDALMD_AREA_OR_POINT); area && std::string(area) == GDALMD_AOP_POINT) {
    result.notes.push_back("PixelIsPoint raster: its elevations are taken at the cell centres");
  }
  require_metre_units(srs, *dataset->GetRasterBand(1), name);

  if (crs.kind == CrsOption::Kind::from_file && srs.IsGeographic()) {
    const int epsg = utm_epsg_for(spec);
    dataset = reproject_to_utm(*dataset, name, epsg);
    spec = raster_grid(*dataset, name);
    srs = *dataset->GetSpatialRef();
    std::ostringstream note;
    note.precision(3);
    note << "DEM in a geographic CRS: reprojected to WGS 84 / UTM (EPSG:" << epsg << "), " << spec.cell_width()
         << " m cells";
    result.notes.push_back(note.str());
  }
  spec.crs_wkt = crs.kind == CrsOption::Kind::local ? std::string() : wkt_of(&srs);
  spec.nodata = input_nodata;
  require_plausible_grid(spec, name);

  GDALRasterBand* band = dataset->GetRasterBand(1);
  int has_nodata = 0;
  const double file_nodata = band->GetNoDataValue(&has_nodata);
  std::vector<double> values(spec.cell_count());
  CPLErrorReset();
  if (band->RasterIO(GF_Read, 0, 0, spec.width, spec.height, values.data(), spec.width, spec.height, GDT_Float64, 0, 0) != CE_None) {
    throw InputError(name + ": cannot read its elevations: " + last_gdal_error("read error"));
  }
  for (double& v : values) {
    if (!std::isfinite(v) || (has_nodata && v == file_nodata)) v = input_nodata;
  }
  treat_impossible_elevations(values, input_nodata, name, result.notes);
  result.elevation = Grid<double>(spec, std::move(values));
  if (const std::size_t zeros = mark_zero_border_as_nodata(result.elevation); zeros > 0) {
    result.notes.push_back(std::to_string(zeros) + " cells of elevation 0 m around the border taken as nodata");
  }
  std::size_t valid = 0;
  for (std::size_t i = 0; i < result.elevation.size(); ++i) valid += result.elevation.is_valid(i) ? 1 : 0;
  if (valid == 0) throw InputError(name + ": has no valid elevation (every cell is nodata)");
  result.crs_name = crs_display_name(spec.crs_wkt);
  return result;
}

}  // namespace talus::gis
