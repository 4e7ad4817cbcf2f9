// trajectories.gpkg through OGR's GeoPackage driver: the layer, its fields, the software version
// in the layer's metadata, and every feature in one transaction. The fields' aliases are set for
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
    VectorField{"source_id", OFTInteger64, "Release source"},
    VectorField{"stop_reason", OFTString, "Stop reason"},
    VectorField{"max_energy_kj", OFTReal, "Maximum kinetic energy (kJ)"},
    VectorField{"runout_length_m", OFTReal, "Runout length (m)"},
};

// The GeoPackage layer, its metadata and attributes.
const VectorLayerSpec kLayer{"trajectories", wkbLineString25D, "Rock-fall trajectories",
                             "Sampled rock-fall trajectories: centre of mass of the rock, x and y in the CRS, z elevation "
                             "(m); energy in kJ, length in m",
                             kFields};

void add_feature(OGRLayer& layer, const TrajectoryLine& line, const std::filesystem::path& path) {
  OGRFeature feature(layer.GetLayerDefn());
  feature.SetField("run_id", static_cast<GIntBig>(line.run_id));
  feature.SetField("source_id", static_cast<GIntBig>(line.source_id));
  feature.SetField("stop_reason", to_string(line.stop_reason));
  feature.SetField("max_energy_kj", line.max_energy);
  feature.SetField("runout_length_m", line.runout_length);
  if (line.points.size() >= 2) {
    auto geometry = std::make_unique<OGRLineString>();
    geometry->setNumPoints(static_cast<int>(line.points.size()), FALSE);
    for (std::size_t i = 0; i < line.points.size(); ++i) {
      const Eigen::Vector3d& p = line.points[i];
      geometry->setPoint(static_cast<int>(i), p.x(), p.y(), p.z());
    }
    feature.SetGeometryDirectly(geometry.release());
  }
  check_written(layer.CreateFeature(&feature), path, "writing a trajectory");
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
    check_written(dataset->StartTransaction(), path, "starting the transaction");
    for (const TrajectoryLine& line : lines) add_feature(layer, line, path);
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
