// particles.gpkg through OGR's GeoPackage driver (one layer, its fields, the software version,
// every feature in one transaction), its QML style and its layer definition (QLR), written in
// the formats QGIS 3.22 reads.
// QGIS 3.22 resets a layer's temporal settings after loading the style beside it, but guesses
// them from the field names: a DateTime field named start_time and one named end_time give
// "start and end date/time from fields" preselected, so the animation is one tick away (the
// style's temporal part applies when the style is loaded explicitly). docs/layers.md, particles.gpkg.
#include "talus/gis/particle_snapshot_writer.hpp"

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "talus/gis/gdal_dataset.hpp"
#include "talus/gis/xml_text.hpp"

namespace talus::gis {
namespace {

// The attributes in the layer's order.
constexpr std::array kFields{
    VectorField{"time_s", OFTReal, "Time after release (s)"},
    VectorField{"start_time", OFTDateTime, "Shown from (the release's date-time + time_s)"},
    VectorField{"end_time", OFTDateTime, "Shown until"},
    VectorField{"depth_m", OFTReal, "Flow depth (m)"},
    VectorField{"speed_m_s", OFTReal, "Speed (m/s)"},
    VectorField{"mass_kg", OFTReal, "Mass (kg)"},
    VectorField{"radius_m", OFTReal, "Particle radius (m)"},
};

// The flow_depth_max classes (m, gis/styles/make_styles.py): upper limits and one colour per
// class plus one above the last limit.
constexpr std::array kDepthLimits{0.1, 0.25, 0.5, 1.0, 2.0, 5.0};
constexpr std::array kDepthColours{"239,243,255", "198,219,239", "158,202,225", "107,174,214",
                                   "66,146,198",  "33,113,181",  "8,69,148"};

// end_time lies this much (s) before the next snapshot's start_time: QGIS hands the temporal
// filter to the GeoPackage as a comparison of date-time texts, in which an end equal to a
// frame's start counts as after it, so two snapshots would show in one frame.
constexpr double kEndGap = 0.001;

// The GeoPackage layer, its metadata and attributes.
const VectorLayerSpec kLayer{"particles", wkbPoint25D, "Mud-flow particles",
                             "Mud-flow particle snapshots: foot of each particle's column, x and y in the CRS, z ground "
                             "elevation (m); shown from start_time to end_time, the release's date-time + time_s",
                             kFields, false};

// Sets a DateTime field to `start` (s after 1970-01-01) + `seconds` (s), to the millisecond,
// without a time zone (particle_snapshot_writer.hpp).
void set_time(OGRFeature& feature, const char* field, std::int64_t start, double seconds) {
  const long long milliseconds = std::llround(seconds * 1000.0);
  const std::time_t whole = static_cast<std::time_t>(start + milliseconds / 1000);
  std::tm utc{};
  gmtime_r(&whole, &utc);
  const float second = static_cast<float>(utc.tm_sec) + static_cast<float>(milliseconds % 1000) / 1000.0f;
  feature.SetField(feature.GetFieldIndex(field), utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday, utc.tm_hour,
                   utc.tm_min, second, 0);  // 0: no time zone in OGR's flag
}

// Writes the particles of one snapshot, shown from its time to `shown_until` (s).
void add_snapshot(OGRLayer& layer, const ParticleSnapshot& snapshot, double shown_until, std::int64_t start,
                  const std::filesystem::path& path) {
  const std::size_t count = snapshot.x.size();
  for (const auto* column : {&snapshot.y, &snapshot.z, &snapshot.depth, &snapshot.speed, &snapshot.mass, &snapshot.radius}) {
    if (column->size() != count) throw std::logic_error("particle snapshot columns of different lengths");
  }
  for (std::size_t i = 0; i < count; ++i) {
    OGRFeature feature(layer.GetLayerDefn());
    feature.SetField("time_s", snapshot.time);
    set_time(feature, "start_time", start, snapshot.time);
    set_time(feature, "end_time", start, shown_until);
    feature.SetField("depth_m", snapshot.depth[i]);
    feature.SetField("speed_m_s", snapshot.speed[i]);
    feature.SetField("mass_kg", snapshot.mass[i]);
    feature.SetField("radius_m", snapshot.radius[i]);
    feature.SetGeometryDirectly(new OGRPoint(snapshot.x[i], snapshot.y[i], snapshot.z[i]));
    check_written(layer.CreateFeature(&feature), path, "writing a particle");
  }
}

void remove_quietly(const std::filesystem::path& path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}

// "0.1" for a class limit, as QGIS labels it.
std::string limit_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// The elements of the particles' style (temporal settings, renderer, aliases), shared by the QML
// style and the layer definition.
std::string style_elements() {
  std::ostringstream qml;
  qml << "  <temporal enabled=\"1\" mode=\"2\" startField=\"start_time\" endField=\"end_time\" startExpression=\"\" "
         "endExpression=\"\" durationField=\"\" durationUnit=\"s\" fixedDuration=\"0\" accumulate=\"0\" limitMode=\"0\">\n"
      << "    <fixedRange>\n      <start></start>\n      <end></end>\n    </fixedRange>\n  </temporal>\n"
      << "  <renderer-v2 type=\"graduatedSymbol\" attr=\"depth_m\" graduatedMethod=\"GraduatedColor\" symbollevels=\"0\" "
         "enableorderby=\"0\" forceraster=\"0\" referencescale=\"-1\">\n    <ranges>\n";
  for (std::size_t k = 0; k < kDepthColours.size(); ++k) {
    const std::string lower = k == 0 ? "0" : limit_text(kDepthLimits[k - 1]);
    const std::string upper = k < kDepthLimits.size() ? limit_text(kDepthLimits[k]) : "inf";
    const std::string label = k < kDepthLimits.size() ? lower + " - " + upper + " m" : "&gt; " + lower + " m";
    qml << "      <range symbol=\"" << k << "\" label=\"" << label << "\" lower=\"" << lower << "\" upper=\"" << upper
        << "\" render=\"true\"/>\n";
  }
  qml << "    </ranges>\n    <symbols>\n";
  for (std::size_t k = 0; k < kDepthColours.size(); ++k) {
    qml << "      <symbol type=\"marker\" name=\"" << k << "\" alpha=\"1\" clip_to_extent=\"1\" force_rhr=\"0\">\n"
        << "        <layer class=\"SimpleMarker\" enabled=\"1\" locked=\"0\" pass=\"0\">\n"
        << "          <prop k=\"name\" v=\"circle\"/>\n"
        << "          <prop k=\"color\" v=\"" << kDepthColours[k] << ",255\"/>\n"
        << "          <prop k=\"outline_style\" v=\"no\"/>\n"
        << "          <prop k=\"size\" v=\"1.6\"/>\n"
        << "          <prop k=\"size_unit\" v=\"MM\"/>\n"
        << "        </layer>\n      </symbol>\n";
  }
  qml << "    </symbols>\n  </renderer-v2>\n  <aliases>\n";
  for (std::size_t i = 0; i < kFields.size(); ++i) {
    qml << "    <alias field=\"" << kFields[i].name << "\" index=\"" << i + 1 << "\" name=\"" << kFields[i].alias << "\"/>\n";
  }
  qml << "  </aliases>\n  <layerGeometryType>0</layerGeometryType>\n";
  return qml.str();
}

}  // namespace

std::optional<std::int64_t> parse_snapshot_start(const std::string& text) {
  // Exactly YYYY-MM-DDTHH:MM:SS, then nothing or "Z".
  const bool shaped = (text.size() == 19 || (text.size() == 20 && text.back() == 'Z')) && text[4] == '-' &&
                      text[7] == '-' && text[10] == 'T' && text[13] == ':' && text[16] == ':';
  if (!shaped) return std::nullopt;
  for (const std::size_t at : {0, 1, 2, 3, 5, 6, 8, 9, 11, 12, 14, 15, 17, 18}) {
    if (text[at] < '0' || text[at] > '9') return std::nullopt;
  }
  const auto number = [&](std::size_t at, std::size_t digits) { return std::stoi(text.substr(at, digits)); };
  std::tm parts{};
  parts.tm_year = number(0, 4) - 1900;
  parts.tm_mon = number(5, 2) - 1;
  parts.tm_mday = number(8, 2);
  parts.tm_hour = number(11, 2);
  parts.tm_min = number(14, 2);
  parts.tm_sec = number(17, 2);
  if (parts.tm_year + 1900 < 1000) return std::nullopt;
  const std::tm given = parts;
  const std::time_t seconds = timegm(&parts);
  // timegm normalises a day or hour out of range (February 30th): such a text is no date-time.
  if (parts.tm_mday != given.tm_mday || parts.tm_mon != given.tm_mon || parts.tm_hour != given.tm_hour ||
      parts.tm_min != given.tm_min || parts.tm_sec != given.tm_sec) {
    return std::nullopt;
  }
  return static_cast<std::int64_t>(seconds);
}

void write_particle_snapshots(const std::filesystem::path& path, const std::vector<ParticleSnapshot>& snapshots,
                              double interval, const std::string& crs_wkt, std::int64_t start) {
  if (!(interval > kEndGap)) throw std::invalid_argument("particle snapshots need an interval > 0.001 s");
  ensure_gdal_ready();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
  if (driver == nullptr) throw std::runtime_error("cannot write " + path.string() + ": GDAL has no GPKG driver");
  std::error_code error;
  std::filesystem::remove(path, error);  // SQLite would open an existing file instead of replacing it
  if (error) throw std::runtime_error("cannot replace " + path.string() + ": " + error.message());

  CPLErrorReset();
  GDALDatasetUniquePtr dataset(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!dataset) write_failure(path, "creating the GeoPackage");
  CPLErrorReset();  // a temporary name's extension other than .gpkg is only a warning
  try {
    OGRLayer& layer = create_vector_layer(*dataset, path, crs_wkt, kLayer);
    check_written(dataset->StartTransaction(), path, "starting the transaction");
    for (std::size_t k = 0; k < snapshots.size(); ++k) {
      const double next = k + 1 < snapshots.size() ? snapshots[k + 1].time : snapshots[k].time + interval;
      add_snapshot(layer, snapshots[k], std::max(snapshots[k].time, next - kEndGap), start, path);
    }
    check_written(dataset->CommitTransaction(), path, "committing the features");
    dataset.reset();  // closes the file; a failed close shows in the error state only
    if (CPLGetLastErrorType() == CE_Failure) write_failure(path, "closing the GeoPackage");
  } catch (...) {
    dataset.reset();
    remove_quietly(path);
    throw;
  }
}

std::string particle_style() {
  return "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n"
         "<qgis version=\"3.22.16-Białowieża\" styleCategories=\"Symbology|Fields|Temporal\">\n" +
         style_elements() + "</qgis>\n";
}

std::string particle_layer_definition(const std::string& crs_wkt) {
  const char* const source = "./particles.gpkg|layername=particles";
  std::ostringstream qlr;
  qlr << "<!DOCTYPE qgis-layer-definition>\n<qlr>\n"
      << "  <layer-tree-group name=\"\" expanded=\"1\" checked=\"Qt::Checked\">\n"
      << "    <layer-tree-layer providerKey=\"ogr\" name=\"Mud-flow particles\" expanded=\"1\" source=\"" << source
      << "\" checked=\"Qt::Checked\" id=\"talus_particles\"/>\n"
      << "  </layer-tree-group>\n  <maplayers>\n"
      << "    <maplayer type=\"vector\" geometry=\"Point\" wkbType=\"PointZ\" styleCategories=\"AllStyleCategories\">\n"
      << "      <id>talus_particles</id>\n      <datasource>" << source << "</datasource>\n"
      << "      <layername>Mud-flow particles</layername>\n";
  if (!crs_wkt.empty()) {
    qlr << "      <srs>\n        <spatialrefsys nativeFormat=\"Wkt\">\n          <wkt>" << xml_escaped(crs_wkt)
        << "</wkt>\n        </spatialrefsys>\n      </srs>\n";
  }
  qlr << "      <provider encoding=\"UTF-8\">ogr</provider>\n" << style_elements() << "    </maplayer>\n  </maplayers>\n</qlr>\n";
  return qlr.str();
}


void add_particle_snapshots(LayerWriter& writer, const std::vector<ParticleSnapshot>& snapshots, double interval,
                            const std::string& crs_wkt, std::int64_t start) {
  write_particle_snapshots(writer.temporary_path("particles.gpkg"), snapshots, interval, crs_wkt, start);
  for (const auto& [name, text] : {std::pair{"particles.qml", particle_style()},
                                   std::pair{"particles.qlr", particle_layer_definition(crs_wkt)}}) {
    std::ofstream file(writer.temporary_path(name), std::ios::binary);
    file.write(text.data(), static_cast<std::streamsize>(text.size()));
    file.close();
    if (!file) throw std::runtime_error("cannot write " + (writer.folder() / name).string());
  }
}

}  // namespace talus::gis
