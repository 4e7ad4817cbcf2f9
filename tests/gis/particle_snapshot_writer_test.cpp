// particles.gpkg (issue 5): mud-flow particle snapshots as 3D points with their time span, read
// back with OGR, written as part of a layer set, and played by QGIS's temporal controller.
#include "talus/gis/particle_snapshot_writer.hpp"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "talus/gis/gdal_dataset.hpp"
#include "test_paths.hpp"

namespace talus::gis {
namespace {

namespace fs = std::filesystem;

std::string epsg_wkt(int code) {
  OGRSpatialReference srs;
  srs.importFromEPSG(code);
  return wkt_of(&srs);
}

// Three particles at release, two of them 0.5 s later, and one late snapshot past an hour (to
// check the clock's hours, minutes and milliseconds).
std::vector<ParticleSnapshot> sample_snapshots() {
  ParticleSnapshot first{.time = 0.0,
                         .x = {255630.0, 255635.0, 255640.0},
                         .y = {380300.0, 380302.5, 380305.0},
                         .z = {1400.25, 1399.5, 1398.75},
                         .depth = {1.8, 1.5, 0.05},
                         .speed = {0.0, 0.0, 0.0},
                         .mass = {45000.0, 37500.0, 1250.0},
                         .radius = {6.0, 6.0, 3.0}};
  ParticleSnapshot second{.time = 0.5,
                          .x = {255631.0, 255636.0},
                          .y = {380299.0, 380301.0},
                          .z = {1399.0, 1398.0},
                          .depth = {1.7, 1.4},
                          .speed = {2.5, 3.25},
                          .mass = {45000.0, 37500.0},
                          .radius = {6.0, 6.0}};
  ParticleSnapshot late{.time = 3725.25,
                        .x = {255700.0},
                        .y = {380100.0},
                        .z = {1200.0},
                        .depth = {0.3},
                        .speed = {0.125},
                        .mass = {45000.0},
                        .radius = {3.0}};
  return {first, second, late};
}

GDALDatasetUniquePtr open_vector(const fs::path& path) {
  ensure_gdal_ready();
  return GDALDatasetUniquePtr(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
}

// The release at 2000-01-01T00:00:00, the default clock (s after 1970-01-01).
constexpr std::int64_t kStart = 946684800;

// "YYYY/MM/DD HH:MM:SS.sss" as OGR prints a DateTime field without time zone.
std::string time_text(OGRFeature& feature, const char* field) { return feature.GetFieldAsString(field); }

TEST(ParticleSnapshotWriter, WritesEveryParticleOfEverySnapshotWithItsTimeSpan) {
  const auto folder = test::fresh_folder("particles_fields");
  const auto path = folder / "particles.gpkg";
  const auto snapshots = sample_snapshots();
  write_particle_snapshots(path, snapshots, 0.5, epsg_wkt(31287), kStart);

  const auto dataset = open_vector(path);
  ASSERT_TRUE(dataset);
  OGRLayer* layer = dataset->GetLayerByName("particles");
  ASSERT_NE(layer, nullptr);
  EXPECT_EQ(layer->GetGeomType(), wkbPoint25D);
  EXPECT_EQ(layer->GetSpatialRef()->GetAuthorityCode(nullptr), std::string("31287"));
  ASSERT_EQ(layer->GetFeatureCount(), 6);
  layer->ResetReading();
  for (const ParticleSnapshot& snapshot : snapshots) {
    for (std::size_t i = 0; i < snapshot.x.size(); ++i) {
      const std::unique_ptr<OGRFeature> feature(layer->GetNextFeature());
      ASSERT_TRUE(feature);
      // Reals are stored as doubles: exact.
      EXPECT_EQ(feature->GetFieldAsDouble("time_s"), snapshot.time);
      EXPECT_EQ(feature->GetFieldAsDouble("depth_m"), snapshot.depth[i]);
      EXPECT_EQ(feature->GetFieldAsDouble("speed_m_s"), snapshot.speed[i]);
      EXPECT_EQ(feature->GetFieldAsDouble("mass_kg"), snapshot.mass[i]);
      EXPECT_EQ(feature->GetFieldAsDouble("radius_m"), snapshot.radius[i]);
      const OGRGeometry* geometry = feature->GetGeometryRef();
      ASSERT_NE(geometry, nullptr);
      ASSERT_EQ(geometry->getGeometryType(), wkbPoint25D);
      EXPECT_EQ(geometry->toPoint()->getX(), snapshot.x[i]);
      EXPECT_EQ(geometry->toPoint()->getY(), snapshot.y[i]);
      EXPECT_EQ(geometry->toPoint()->getZ(), snapshot.z[i]);
      if (snapshot.time == 0.5) {
        EXPECT_EQ(time_text(*feature, "start_time"), "2000/01/01 00:00:00.500");
        EXPECT_EQ(time_text(*feature, "end_time"), "2000/01/01 01:02:05.249");  // 1 ms before the next
      }
      if (snapshot.time > 3600.0) {
        EXPECT_EQ(time_text(*feature, "start_time"), "2000/01/01 01:02:05.250");
        EXPECT_EQ(time_text(*feature, "end_time"), "2000/01/01 01:02:05.749");  // the last: one interval
      }
    }
  }
  EXPECT_STREQ(layer->GetMetadataItem("TALUS_VERSION"), TALUS_VERSION);
}

TEST(ParticleSnapshotWriter, LocalCoordinatesGetTheUndefinedCartesianSrs) {
  const auto folder = test::fresh_folder("particles_local");
  const auto path = folder / "particles.gpkg";
  write_particle_snapshots(path, sample_snapshots(), 1.0, "", kStart);
  const auto dataset = open_vector(path);
  ASSERT_TRUE(dataset);
  const OGRSpatialReference* srs = dataset->GetLayer(0)->GetSpatialRef();
  ASSERT_NE(srs, nullptr);
  EXPECT_TRUE(srs->IsLocal());
  EXPECT_FALSE(srs->IsGeographic());
}

TEST(ParticleSnapshotWriter, StartTimeIsADateTimeWithoutZone) {
  EXPECT_EQ(parse_snapshot_start("2000-01-01T00:00:00"), kStart);
  EXPECT_EQ(parse_snapshot_start("2000-01-01T00:00:00Z"), kStart);
  EXPECT_EQ(parse_snapshot_start("2024-06-13T14:30:05"), std::int64_t{1718289005});
  for (const char* bad : {"2024-02-30T00:00:00", "2024-06-13", "2024-06-13T14:30:05+02:00", "0999-01-01T00:00:00",
                          "yesterday", ""}) {
    EXPECT_FALSE(parse_snapshot_start(bad).has_value()) << bad;
  }
}

TEST(ParticleSnapshotWriter, ClockStartsAtTheGivenDateTime) {
  const auto path = test::fresh_folder("particles_start") / "particles.gpkg";
  write_particle_snapshots(path, sample_snapshots(), 0.5, epsg_wkt(31287), *parse_snapshot_start("2024-06-13T14:30:00"));
  const auto dataset = open_vector(path);
  ASSERT_TRUE(dataset);
  OGRLayer* layer = dataset->GetLayerByName("particles");
  const std::unique_ptr<OGRFeature> first(layer->GetNextFeature());
  EXPECT_EQ(time_text(*first, "start_time"), "2024/06/13 14:30:00");
}

TEST(ParticleSnapshotWriter, RefusesUnevenColumnsAndLeavesNoFile) {
  const auto folder = test::fresh_folder("particles_uneven");
  auto snapshots = sample_snapshots();
  snapshots[1].mass.pop_back();
  EXPECT_THROW(write_particle_snapshots(folder / "particles.gpkg", snapshots, 0.5, epsg_wkt(31287), kStart), std::logic_error);
  EXPECT_FALSE(fs::exists(folder / "particles.gpkg"));
  EXPECT_THROW(write_particle_snapshots(folder / "particles.gpkg", sample_snapshots(), 0.0, "", kStart), std::invalid_argument);
}

TEST(ParticleSnapshotWriter, JoinsALayerSetAndAppearsOnlyOnCommit) {
  const auto folder = test::fresh_folder("particles_set");
  {
    LayerWriter writer(folder / "out", {});
    add_particle_snapshots(writer, sample_snapshots(), 0.5, epsg_wkt(31287), kStart);
    EXPECT_FALSE(fs::exists(folder / "out" / "particles.gpkg"));
    writer.commit();
  }
  EXPECT_TRUE(fs::exists(folder / "out" / "particles.gpkg"));
  EXPECT_TRUE(fs::exists(folder / "out" / "particles.qlr"));
  std::ifstream qml(folder / "out" / "particles.qml");
  std::string style((std::istreambuf_iterator<char>(qml)), std::istreambuf_iterator<char>());
  EXPECT_EQ(style, particle_style());
  {
    LayerWriter abandoned(folder / "abandoned", {});
    add_particle_snapshots(abandoned, sample_snapshots(), 0.5, epsg_wkt(31287), kStart);
  }
  EXPECT_FALSE(fs::exists(folder / "abandoned"));  // a set never committed creates nothing
}

// Opens particles.gpkg in QGIS as a user would: points with Z, coloured by depth_m with the seven
// flow_depth_max classes, aliases from the style; the temporal settings QGIS preselects from the
// field names are start_time and end_time; once the style is loaded explicitly the layer is
// temporal, and each frame of the animation shows the particles of exactly one snapshot (the
// latest at the frame's start), whole seconds or not, and none after the last one's interval.
constexpr const char* kQgisCheck = R"py(
import os, sys
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
from qgis.core import (QgsApplication, QgsVectorLayer, QgsWkbTypes, QgsDateTimeRange, QgsLayerDefinition, QgsProject,
                       QgsVectorLayerTemporalContext, QgsFeatureRequest, QgsVectorLayerTemporalProperties)
from qgis.PyQt.QtCore import QDateTime, QDate, QTime, Qt
app = QgsApplication([], False)
app.initQgis()
problems = []
layer = QgsVectorLayer(sys.argv[1], "particles", "ogr")
if not layer.isValid():
    problems.append("QGIS cannot open it")
else:
    if layer.geometryType() != QgsWkbTypes.PointGeometry or not QgsWkbTypes.hasZ(layer.wkbType()):
        problems.append("not 3D points: " + QgsWkbTypes.displayString(layer.wkbType()))
    renderer = layer.renderer()
    if renderer.type() != "graduatedSymbol" or renderer.classAttribute() != "depth_m" or len(renderer.ranges()) != 7:
        problems.append("not the style's 7 depth classes: " + renderer.type())
    elif renderer.rangeForValue(1.8) is None or renderer.rangeForValue(1.8).upperValue() != 2:
        problems.append("1.8 m is not in the class 1 - 2 m")
    if layer.attributeAlias(layer.fields().indexOf("depth_m")) != "Flow depth (m)":
        problems.append("depth_m has not the style's alias")
    temporal = layer.temporalProperties()
    if temporal.startField() != "start_time" or temporal.endField() != "end_time" or \
       temporal.mode() != QgsVectorLayerTemporalProperties.ModeFeatureDateTimeStartAndEndFromFields:
        problems.append("QGIS does not preselect start_time and end_time: %s %s" % (temporal.startField(), temporal.endField()))
    layer.loadNamedStyle(os.path.splitext(sys.argv[1])[0] + ".qml")
    if not temporal.isActive():
        problems.append("the style does not make the layer temporal")
    context = QgsVectorLayerTemporalContext()
    context.setLayer(layer)
    at = lambda ms: QDateTime(QDate(2000, 1, 1), QTime(0, 0, 0).addMSecs(ms))
    # (frame start, frame end) in ms after release -> time_s of the particles shown.
    frames = [((0, 500), [0.0] * 3), ((500, 1000), [0.5] * 2), ((250, 500), [0.0] * 3), ((1000, 2000), [0.5] * 2),
              ((3725250, 3726000), [3725.25]), ((3725750, 3726000), [])]
    for (begin, end), expected in frames:
        expression = temporal.createFilterString(context, QgsDateTimeRange(at(begin), at(end), True, False))
        shown = [f["time_s"] for f in layer.getFeatures(QgsFeatureRequest().setFilterExpression(expression))]
        if shown != expected:
            problems.append("frame [%d ms, %d ms) shows %s, expected %s" % (begin, end, shown, expected))
    # A map set to one snapshot's instant shows that snapshot (a stored time zone hid them all).
    for ms, expected in ((0, [0.0] * 3), (500, [0.5] * 2), (3725250, [3725.25])):
        expression = temporal.createFilterString(context, QgsDateTimeRange(at(ms), at(ms)))
        shown = [f["time_s"] for f in layer.getFeatures(QgsFeatureRequest().setFilterExpression(expression))]
        if shown != expected:
            problems.append("instant %d ms shows %s, expected %s" % (ms, shown, expected))
del layer
# The layer definition beside it opens the layer styled with its animation on.
loaded, message = QgsLayerDefinition.loadLayerDefinition(os.path.splitext(sys.argv[1])[0] + ".qlr",
                                                         QgsProject.instance(), QgsProject.instance().layerTreeRoot())
layers = list(QgsProject.instance().mapLayers().values())
if not loaded or len(layers) != 1 or not layers[0].isValid():
    problems.append("particles.qlr does not load one valid layer: " + message)
else:
    if not layers[0].temporalProperties().isActive():
        problems.append("particles.qlr loads the layer with its animation off")
    if layers[0].renderer().type() != "graduatedSymbol" or layers[0].featureCount() != 6:
        problems.append("particles.qlr: renderer %s, %d features" % (layers[0].renderer().type(), layers[0].featureCount()))
    if layers[0].crs().authid() != "EPSG:31287":
        problems.append("particles.qlr: CRS " + layers[0].crs().authid())
QgsProject.instance().removeAllMapLayers()
app.exitQgis()
for p in problems:
    print(p)
sys.exit(1 if problems else 0)
)py";

TEST(ParticleSnapshotWriter, PlaysInTheQgisTemporalController) {
  const fs::path python = "/usr/bin/python3";
  if (!fs::exists(python)) GTEST_SKIP() << python << " (with python3-qgis) is not installed";
  const auto folder = test::fresh_folder("particles_qgis");
  {
    LayerWriter writer(folder, {});
    add_particle_snapshots(writer, sample_snapshots(), 0.5, epsg_wkt(31287), kStart);
    writer.commit();
  }
  const auto script = folder / "check_particles.py";
  std::ofstream(script) << kQgisCheck;
  const std::string command = python.string() + " " + script.string() + " " + (folder / "particles.gpkg").string();
  const int status = std::system(command.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

}  // namespace
}  // namespace talus::gis
