// trajectories.gpkg (docs/architecture.md section 3): 3D lines with their attributes, read back with OGR
// and opened in QGIS with their style.
#include "talus/gis/trajectory_writer.hpp"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <sys/wait.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "talus/gis/folder_manifest.hpp"
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

TrajectoryVertex vertex(double x, double y, double z, double time) {
  return {{x, y, z}, time, 2.0 * time, 0.5 * time, 0.25 * time};
}

// Three trajectories down a slope in EPSG:31287 metres, one with a source id beyond 32 bits and
// one from a raster cell (no release feature).
std::vector<TrajectoryLine> sample_lines() {
  std::vector<TrajectoryLine> lines(3);
  lines[0] = {.source_id = 7, .run_id = 0, .release_fid = 3, .stop_reason = StopReason::at_rest, .max_energy = 12.5,
              .runout_length = 80.25, .vertices = {}};
  for (int i = 0; i < 50; ++i)
    lines[0].vertices.push_back(vertex(612000.0 + 1.5 * i, 385000.0 - 0.5 * i, 1500.0 - 0.75 * i + 0.125, 0.1 * i));
  lines[1] = {.source_id = 7, .run_id = 1, .release_fid = 3, .stop_reason = StopReason::left_dem, .max_energy = 4200.0,
              .runout_length = 310.5,
              .vertices = {vertex(612010.0, 384990.0, 1490.0, 0.0), vertex(612100.0, 384900.0, 1400.5, 7.5)}};
  lines[2] = {.source_id = std::uint64_t{1} << 40, .run_id = 3, .release_fid = kNoReleaseFeature,
              .stop_reason = StopReason::max_time, .max_energy = 0.0, .runout_length = 0.0,
              .vertices = {vertex(612020.0, 384980.0, 1480.0, 0.0), vertex(612021.0, 384979.0, 1479.0, 1.0)}};
  return lines;
}

GDALDatasetUniquePtr open_vector(const fs::path& path) {
  ensure_gdal_ready();
  return GDALDatasetUniquePtr(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
}

// The srs_id of the GeoPackage's one geometry table.
int srs_id_of(GDALDataset& dataset) {
  OGRLayer* result = dataset.ExecuteSQL("SELECT srs_id FROM gpkg_geometry_columns", nullptr, nullptr);
  if (result == nullptr) return -999;
  const std::unique_ptr<OGRFeature> row(result->GetNextFeature());
  const int id = row ? row->GetFieldAsInteger(0) : -999;
  dataset.ReleaseResultSet(result);
  return id;
}

std::set<std::string> names_in(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.insert(entry.path().filename().string());
  return names;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every feature's attributes and points equal the line's, in order.
void expect_features_equal(OGRLayer& layer, const std::vector<TrajectoryLine>& lines) {
  ASSERT_EQ(layer.GetFeatureCount(), static_cast<GIntBig>(lines.size()));
  layer.ResetReading();
  for (const TrajectoryLine& line : lines) {
    const std::unique_ptr<OGRFeature> feature(layer.GetNextFeature());
    ASSERT_TRUE(feature);
    EXPECT_EQ(feature->GetFieldAsInteger64("run_id"), static_cast<GIntBig>(line.run_id));
    EXPECT_EQ(feature->GetFieldAsInteger64("source_id"), static_cast<GIntBig>(line.source_id));
    if (line.release_fid == kNoReleaseFeature) {
      EXPECT_TRUE(feature->IsFieldNull(feature->GetFieldIndex("release_fid")));
    } else {
      EXPECT_EQ(feature->GetFieldAsInteger64("release_fid"), line.release_fid);
    }
    EXPECT_STREQ(feature->GetFieldAsString("stop_reason"), to_string(line.stop_reason));
    EXPECT_EQ(feature->GetFieldAsDouble("max_energy_kj"), line.max_energy);
    EXPECT_EQ(feature->GetFieldAsDouble("runout_length_m"), line.runout_length);
    const OGRGeometry* geometry = feature->GetGeometryRef();
    ASSERT_NE(geometry, nullptr);
    ASSERT_EQ(geometry->getGeometryType(), wkbLineStringZM);
    const auto* points = geometry->toLineString();
    ASSERT_EQ(points->getNumPoints(), static_cast<int>(line.vertices.size()));
    for (int i = 0; i < points->getNumPoints(); ++i) {
      const TrajectoryVertex& v = line.vertices[static_cast<std::size_t>(i)];
      EXPECT_EQ(points->getX(i), v.position.x()) << "point " << i;
      EXPECT_EQ(points->getY(i), v.position.y()) << "point " << i;
      EXPECT_EQ(points->getZ(i), v.position.z()) << "point " << i;
      EXPECT_EQ(points->getM(i), v.time) << "point " << i;
    }
  }
}

// The vertex layer holds every vertex of every line, in order, with its values and the
// horizontal distance along the path.
void expect_vertices_equal(OGRLayer& layer, const std::vector<TrajectoryLine>& lines) {
  std::size_t total = 0;
  for (const TrajectoryLine& line : lines) total += line.vertices.size();
  ASSERT_EQ(layer.GetFeatureCount(), static_cast<GIntBig>(total));
  layer.ResetReading();
  for (const TrajectoryLine& line : lines) {
    double distance = 0.0;
    for (std::size_t i = 0; i < line.vertices.size(); ++i) {
      const TrajectoryVertex& v = line.vertices[i];
      if (i > 0) distance += (v.position - line.vertices[i - 1].position).head<2>().norm();
      const std::unique_ptr<OGRFeature> feature(layer.GetNextFeature());
      ASSERT_TRUE(feature);
      EXPECT_EQ(feature->GetFieldAsInteger64("source_id"), static_cast<GIntBig>(line.source_id));
      EXPECT_EQ(feature->GetFieldAsInteger64("run_id"), static_cast<GIntBig>(line.run_id));
      EXPECT_EQ(feature->GetFieldAsInteger("vertex"), static_cast<int>(i));
      EXPECT_EQ(feature->GetFieldAsDouble("time_s"), v.time);
      EXPECT_EQ(feature->GetFieldAsDouble("distance_m"), distance);
      EXPECT_EQ(feature->GetFieldAsDouble("speed_m_s"), v.speed);
      EXPECT_EQ(feature->GetFieldAsDouble("energy_kj"), v.kinetic_energy);
      EXPECT_EQ(feature->GetFieldAsDouble("jump_height_m"), v.jump_height);
      const auto* point = feature->GetGeometryRef()->toPoint();
      EXPECT_EQ(point->getX(), v.position.x());
      EXPECT_EQ(point->getZ(), v.position.z());
    }
  }
}

const fs::path kPython = "/usr/bin/python3";

std::string quoted(const std::string& text) { return "'" + text + "'"; }

// Runs tests/gis/qgis/check_vector_in_qgis.py with the arguments (already quoted).
int check_in_qgis(const std::string& arguments) {
  const auto script = test::source_dir() / "tests/gis/qgis/check_vector_in_qgis.py";
  const int status = std::system((kPython.string() + " " + quoted(script.string()) + " " + arguments).c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(TrajectoryWriter, WritesLinesWithTimeAsMAndTheirVerticesWithTheirAttributesInTheCrs) {
  const auto path = test::fresh_folder("trajectories_crs") / "trajectories.gpkg";
  const auto lines = sample_lines();
  write_trajectories(path, lines, epsg_wkt(31287));

  const auto dataset = open_vector(path);
  ASSERT_TRUE(dataset);
  EXPECT_STREQ(dataset->GetDriver()->GetDescription(), "GPKG");
  ASSERT_EQ(dataset->GetLayerCount(), 2);
  OGRLayer* layer = dataset->GetLayerByName("trajectories");
  ASSERT_NE(layer, nullptr);
  EXPECT_TRUE(OGR_GT_HasZ(layer->GetGeomType()));
  EXPECT_TRUE(OGR_GT_HasM(layer->GetGeomType()));
  EXPECT_EQ(wkbFlatten(layer->GetGeomType()), wkbLineString);
  EXPECT_STREQ(layer->GetMetadataItem("TALUS_VERSION"), TALUS_VERSION);

  const OGRFeatureDefn* definition = layer->GetLayerDefn();
  ASSERT_EQ(definition->GetFieldCount(), 6);
  const std::vector<std::pair<std::string, OGRFieldType>> fields = {{"run_id", OFTInteger64},
                                                                     {"source_id", OFTInteger64},
                                                                     {"release_fid", OFTInteger64},
                                                                     {"stop_reason", OFTString},
                                                                     {"max_energy_kj", OFTReal},
                                                                     {"runout_length_m", OFTReal}};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(definition->GetFieldDefn(i)->GetNameRef(), fields[static_cast<std::size_t>(i)].first);
    EXPECT_EQ(definition->GetFieldDefn(i)->GetType(), fields[static_cast<std::size_t>(i)].second);
  }

  ASSERT_NE(layer->GetSpatialRef(), nullptr);
  OGRSpatialReference expected;
  expected.importFromEPSG(31287);
  expected.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // GDAL's order for layers
  EXPECT_TRUE(layer->GetSpatialRef()->IsSame(&expected));
  EXPECT_EQ(srs_id_of(*dataset), 31287);
  expect_features_equal(*layer, lines);
  OGRLayer* vertices = dataset->GetLayerByName("trajectory_vertices");
  ASSERT_NE(vertices, nullptr);
  EXPECT_TRUE(OGR_GT_HasZ(vertices->GetGeomType()));
  EXPECT_TRUE(vertices->GetSpatialRef()->IsSame(&expected));
  expect_vertices_equal(*vertices, lines);

  OGREnvelope extent;
  ASSERT_EQ(layer->GetExtent(&extent), OGRERR_NONE);
  EXPECT_EQ(extent.MinX, 612000.0);
  EXPECT_EQ(extent.MaxY, 385000.0);
}

TEST(TrajectoryWriter, WritesLocalCoordinatesInTheUndefinedCartesianSrs) {
  const auto path = test::fresh_folder("trajectories_local") / "trajectories.gpkg";
  const auto lines = sample_lines();
  write_trajectories(path, lines, "");
  const auto dataset = open_vector(path);
  ASSERT_TRUE(dataset);
  EXPECT_EQ(srs_id_of(*dataset), -1);  // not 0, the undefined geographic SRS
  OGRLayer* layer = dataset->GetLayerByName("trajectories");
  ASSERT_NE(layer->GetSpatialRef(), nullptr);
  EXPECT_TRUE(layer->GetSpatialRef()->IsLocal());
  EXPECT_EQ(layer->GetSpatialRef()->GetLinearUnits(), 1.0);
  EXPECT_TRUE(OGR_GT_HasZ(layer->GetGeomType()));
  expect_features_equal(*layer, lines);
}

TEST(TrajectoryWriter, KeepsALineOfOnePointAsAFeatureWithoutGeometryAndAnEmptySetAsAnEmptyLayer) {
  const auto folder = test::fresh_folder("trajectories_degenerate");
  const TrajectoryLine stuck{.source_id = 9, .run_id = 2, .stop_reason = StopReason::nodata_area, .max_energy = 0.5,
                             .runout_length = 0.0, .vertices = {vertex(612000.0, 385000.0, 1500.0, 0.0)}};
  write_trajectories(folder / "one.gpkg", {stuck}, epsg_wkt(31287));
  write_trajectories(folder / "none.gpkg", {}, epsg_wkt(31287));

  const auto one = open_vector(folder / "one.gpkg");
  ASSERT_TRUE(one);
  ASSERT_EQ(one->GetLayerByName("trajectories")->GetFeatureCount(), 1);
  const std::unique_ptr<OGRFeature> feature(one->GetLayerByName("trajectories")->GetNextFeature());
  EXPECT_EQ(feature->GetGeometryRef(), nullptr);
  EXPECT_EQ(feature->GetFieldAsInteger64("source_id"), 9);
  EXPECT_STREQ(feature->GetFieldAsString("stop_reason"), to_string(StopReason::nodata_area));

  const auto none = open_vector(folder / "none.gpkg");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->GetLayerByName("trajectories")->GetFeatureCount(), 0);
  EXPECT_TRUE(OGR_GT_HasZ(none->GetLayerByName("trajectories")->GetGeomType()));
}

TEST(TrajectoryWriter, ReplacesAnEarlierFile) {
  const auto path = test::fresh_folder("trajectories_replace") / "trajectories.gpkg";
  write_trajectories(path, sample_lines(), epsg_wkt(31287));
  write_trajectories(path, {sample_lines()[1]}, "");
  const auto dataset = open_vector(path);
  ASSERT_TRUE(dataset);
  ASSERT_EQ(dataset->GetLayerCount(), 2);
  EXPECT_EQ(srs_id_of(*dataset), -1);
  expect_features_equal(*dataset->GetLayerByName("trajectories"), {sample_lines()[1]});
}

TEST(TrajectoryWriter, FailuresNameThePathAndLeaveNoFile) {
  const auto folder = test::fresh_folder("trajectories_failures");
  const auto bad_crs = folder / "bad_crs.gpkg";
  try {
    write_trajectories(bad_crs, sample_lines(), "not a CRS");
    ADD_FAILURE() << "no error for a bad CRS";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(bad_crs.string()), std::string::npos) << error.what();
  }
  const auto no_folder = folder / "missing" / "trajectories.gpkg";
  try {
    write_trajectories(no_folder, sample_lines(), epsg_wkt(31287));
    ADD_FAILURE() << "no error for a missing folder";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(no_folder.string()), std::string::npos) << error.what();
  }
  EXPECT_TRUE(fs::is_empty(folder));
}

TEST(TrajectoryWriter, AddsTheGeoPackageAndItsStyleToALayerSet) {
  const auto folder = test::fresh_folder("trajectories_layer_set");
  {
    LayerWriter writer(folder, {});
    add_trajectories(writer, sample_lines(), epsg_wkt(31287));
    for (const auto& name : names_in(folder)) EXPECT_EQ(name.front(), '.') << name << " is visible before commit";
    writer.commit();
  }
  EXPECT_EQ(names_in(folder), (std::set<std::string>{"trajectories.gpkg", "trajectories.qml", kFolderManifestName}));
  const auto style = embedded_style("trajectories");
  ASSERT_TRUE(style);
  EXPECT_EQ(read_text(folder / "trajectories.qml"), *style);
  EXPECT_EQ(*style, read_text(test::source_dir() / "gis/styles/trajectories.qml"));
  const auto dataset = open_vector(folder / "trajectories.gpkg");
  ASSERT_TRUE(dataset);
  expect_features_equal(*dataset->GetLayerByName("trajectories"), sample_lines());
}

TEST(TrajectoryWriter, LeavesNothingWhenTheSetIsNeverCommitted) {
  const auto folder = test::fresh_folder("trajectories_uncommitted");
  {
    LayerWriter writer(folder, {});
    add_trajectories(writer, sample_lines(), epsg_wkt(31287));
  }
  EXPECT_TRUE(fs::is_empty(folder));
}

TEST(TrajectoryWriter, OpensStyledInQgis) {
  if (!fs::exists(kPython)) GTEST_SKIP() << kPython << " (with python3-qgis) is not installed";
  const auto folder = test::fresh_folder("trajectories_qgis");
  {
    LayerWriter writer(folder, {});
    add_trajectories(writer, sample_lines(), epsg_wkt(31287));
    writer.commit();
  }
  EXPECT_EQ(check_in_qgis("EPSG:31287 " + quoted((folder / "trajectories.gpkg").string()) + " 3"), 0);

  const auto local = test::fresh_folder("trajectories_qgis_local");
  {
    LayerWriter writer(local, {});
    add_trajectories(writer, sample_lines(), "");
    writer.commit();
  }
  EXPECT_EQ(check_in_qgis("local " + quoted((local / "trajectories.gpkg").string()) + " 3"), 0);
}

}  // namespace
}  // namespace talus::gis
