// trajectories.gpkg through OGR's GeoPackage driver: the lines and their vertices as two layers,
// their fields, the software version in each layer's metadata, and every feature in one
// transaction. The fields' aliases are set for
// GDAL versions whose driver stores them (in gpkg_data_columns); GDAL 3.6 drops them, and QGIS
// takes them from trajectories.qml.
#include "talus/gis/trajectory_writer.hpp"

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <array>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <system_error>

#include "talus/gis/gdal_dataset.hpp"

namespace talus::gis {
namespace {

// The attributes in the layer's order; gis/styles/make_styles.py names the same fields.
constexpr std::array kFields{
    VectorField{"run_id", OFTInteger64, "Run"},
    VectorField{"source_id", OFTInteger64, "Release source (0-based, as --only-source)"},
    VectorField{"release_fid", OFTInteger64, "Release feature (FID of the release layer)"},
    VectorField{"stop_reason", OFTString, "Stop reason"},
    VectorField{"max_energy_kj", OFTReal, "Maximum kinetic energy (kJ)"},
    VectorField{"runout_length_m", OFTReal, "Runout length (m)"},
};

// The GeoPackage layer, its metadata and attributes. M is the time since release (s).
const VectorLayerSpec kLayer{"trajectories", wkbLineStringZM, "Rock-fall trajectories",
                             "Sampled rock-fall trajectories: centre of mass of the rock, x and y in the CRS, z elevation "
                             "(m), m time since release (s); energy in kJ, length in m",
                             kFields};

// One point per vertex of every line, with what a profile plot needs (docs/layers.md).
constexpr std::array kVertexFields{
    VectorField{"run_id", OFTInteger64, "Run"},
    VectorField{"source_id", OFTInteger64, "Release source (0-based, as --only-source)"},
    VectorField{"vertex", OFTInteger, "Vertex (0 at the release)"},
    VectorField{"time_s", OFTReal, "Time since release (s)"},
    VectorField{"distance_m", OFTReal, "Horizontal distance along the path (m)"},
    VectorField{"speed_m_s", OFTReal, "Speed (m/s)"},
    VectorField{"energy_kj", OFTReal, "Kinetic energy (kJ)"},
    VectorField{"jump_height_m", OFTReal, "Jump height, centre above the ground (m)"},
};

const VectorLayerSpec kVertexLayer{"trajectory_vertices", wkbPoint25D, "Rock-fall trajectory vertices",
                                   "The vertices of the sampled rock-fall trajectories with time, distance along the "
                                   "path, speed, kinetic energy and jump height at each",
                                   kVertexFields, false};

void set_release_fid(OGRFeature& feature, const TrajectoryLine& line) {
  if (line.release_fid == kNoReleaseFeature) {
    feature.SetFieldNull(feature.GetFieldIndex("release_fid"));
  } else {
    feature.SetField("release_fid", static_cast<GIntBig>(line.release_fid));
  }
}

void add_feature(OGRLayer& layer, const TrajectoryLine& line, const std::filesystem::path& path) {
  OGRFeature feature(layer.GetLayerDefn());
  feature.SetField("run_id", static_cast<GIntBig>(line.run_id));
  feature.SetField("source_id", static_cast<GIntBig>(line.source_id));
  set_release_fid(feature, line);
  feature.SetField("stop_reason", to_string(line.stop_reason));
  feature.SetField("max_energy_kj", line.max_energy);
  feature.SetField("runout_length_m", line.runout_length);
  if (line.vertices.size() >= 2) {
    auto geometry = std::make_unique<OGRLineString>();
    geometry->setNumPoints(static_cast<int>(line.vertices.size()), FALSE);
    for (std::size_t i = 0; i < line.vertices.size(); ++i) {
      const TrajectoryVertex& v = line.vertices[i];
      geometry->setPoint(static_cast<int>(i), v.position.x(), v.position.y(), v.position.z(), v.time);
    }
    feature.SetGeometryDirectly(geometry.release());
  }
  check_written(layer.CreateFeature(&feature), path, "writing a trajectory");
}

void add_vertices(OGRLayer& layer, const TrajectoryLine& line, const std::filesystem::path& path) {
  double distance = 0.0;
  for (std::size_t i = 0; i < line.vertices.size(); ++i) {
    const TrajectoryVertex& v = line.vertices[i];
    if (i > 0) distance += (v.position - line.vertices[i - 1].position).head<2>().norm();
    OGRFeature feature(layer.GetLayerDefn());
    feature.SetField("run_id", static_cast<GIntBig>(line.run_id));
    feature.SetField("source_id", static_cast<GIntBig>(line.source_id));
    feature.SetField("vertex", static_cast<int>(i));
    feature.SetField("time_s", v.time);
    feature.SetField("distance_m", distance);
    feature.SetField("speed_m_s", v.speed);
    feature.SetField("energy_kj", v.kinetic_energy);
    feature.SetField("jump_height_m", v.jump_height);
    feature.SetGeometryDirectly(new OGRPoint(v.position.x(), v.position.y(), v.position.z()));
    check_written(layer.CreateFeature(&feature), path, "writing a trajectory vertex");
  }
}

void remove_quietly(const std::filesystem::path& path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}

}  // namespace

void write_trajectories(const std::filesystem::path& path, const std::vector<TrajectoryLine>& lines,
                        const std::string& crs_wkt) {
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
    OGRLayer& vertices = create_vector_layer(*dataset, path, crs_wkt, kVertexLayer);
    check_written(dataset->StartTransaction(), path, "starting the transaction");
    for (const TrajectoryLine& line : lines) {
      add_feature(layer, line, path);
      add_vertices(vertices, line, path);
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

void add_trajectories(LayerWriter& writer, const std::vector<TrajectoryLine>& lines, const std::string& crs_wkt) {
  const auto style = embedded_style("trajectories");
  if (!style) throw std::logic_error("no QML style in gis/styles for trajectories");
  write_trajectories(writer.temporary_path("trajectories.gpkg"), lines, crs_wkt);
  std::ofstream qml(writer.temporary_path("trajectories.qml"), std::ios::binary);
  qml.write(style->data(), static_cast<std::streamsize>(style->size()));
  qml.close();
  if (!qml) throw std::runtime_error("cannot write " + (writer.folder() / "trajectories.qml").string());
}

}  // namespace talus::gis
